// Test fixture: a guarded header that includes another (guarded.h).
#ifndef OUTER_GUARDED_H
#define OUTER_GUARDED_H

#include "guarded.h"
float outer_value() { return guarded_value(); }

#endif
