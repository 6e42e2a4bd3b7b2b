// The model's constants in the layout of the inverse-dynamics kernel (batch.hpp), stored in
// the Model itself (computed once by its constructor) so that no cache can outlive or
// mismatch the model it came from.
#pragma once

namespace nocdyn::prr3 {

inline constexpr int kLimbs = 3;

namespace batch_detail {

/// Everything constant that one sample needs, gathered from the Model.
struct Constants {
    double e[kLimbs][2];   ///< e_j (eq. 40)
    double n[kLimbs][2];   ///< E e_j
    double Ml[kLimbs][2];  ///< M_j - C at theta = 0 (eq. 41)
    double nB[kLimbs];     ///< n_j . B_j: d_j^M = n_j . M_j - nB_j (eqs. 37-38)
    double eB[kLimbs];     ///< e_j . B_j + s_ref_j: u_j = e_j . A_j - eB_j
    double l, inv_l, rho;  ///< l, 1/l, l_c/l
    double m_s;            ///< slider mass
    double m_L, I_L;       ///< link mass and inertia about its c.o.m.
    double m_P, I_P;       ///< platform mass and inertia about C
    double r;              ///< platform circumradius (scales H's first column in cond_H)
    double max_condition;
};

}  // namespace batch_detail
}  // namespace nocdyn::prr3
