// SPDX-License-Identifier: MIT
// emcv/testing.hpp — statistical checks for Monte Carlo code, framework-neutral, standard library only
// (docs/testing.md). Catch2 users add emcv/testing/catch2.hpp.
#pragma once

#include "testing/chi2_test.hpp"
#include "testing/convergence_test.hpp"
#include "testing/distributions.hpp"
#include "testing/mean_test.hpp"
#include "testing/result.hpp"
