// SPDX-License-Identifier: MIT
// The raw-moment method that moment-buffer denoisers store: running E[x], E[x^2] (and E[xy]) with the same
// weights as ours, variance = E[x^2] - E[x]^2. Used only to show where it breaks (docs/numerics.md section 5).
#pragma once

#include <cstdint>

namespace emcv_numerics {

template <class T>
class raw_moments {
public:
    /// r = w_n / W_n, the same ratio our recurrence uses.
    void push(T x, T y, T r) {
        m_x_ += r * (x - m_x_);
        m_y_ += r * (y - m_y_);
        m_xx_ += r * (x * x - m_xx_);
        m_xy_ += r * (x * y - m_xy_);
        m_yy_ += r * (y * y - m_yy_);
    }
    T mean_x() const { return m_x_; }
    T variance_x() const { return m_xx_ - m_x_ * m_x_; }
    T variance_y() const { return m_yy_ - m_y_ * m_y_; }
    T covariance() const { return m_xy_ - m_x_ * m_y_; }

private:
    T m_x_ = T(0), m_y_ = T(0), m_xx_ = T(0), m_xy_ = T(0), m_yy_ = T(0);
};

}  // namespace emcv_numerics
