// The Fields-of-Experts energy (Roth & Black): the image x is scored by
// E(x) = Σ_i α_i Σ_c log(1 + ½ (s·J_i ⋆ x)_c²) over the cliques c where the s×s filter J_i lies
// inside the image (⋆: correlation, s: the model's input scale); the masked pixels are the
// unknowns, the others stay fixed.
#pragma once

#include <Eigen/SparseCore>
#include <opencv2/core.hpp>

#include "rangefill/inpaint/foe_model.h"

namespace rangefill {

/// E(x) for x CV_64F (already divided by foe_input_divisor); when `gradient` is given it receives
/// ∇E (CV_64F, the size of x): Σ_i s·J_iᵀ ψ_i(y_i), ψ_i(y) = α_i y / (1 + y²/2), y_i = s·J_i ⋆ x.
/// The same value at any thread count.
double foe_energy(const FoeModel& model, const cv::Mat& x, cv::Mat* gradient = nullptr);

/// E(x) up to a constant of the unmasked pixels: the sum over the cliques that cover a pixel of
/// `mask` (CV_8U, non-zero = unknown) only, which is all that inference needs; ∇E is exact at the
/// masked pixels.
/// With `clique_weights` (foe_clique_weights; empty for none), each clique's terms count by its
/// weight.
double foe_energy_of_unknowns(const FoeModel& model, const cv::Mat& x, const cv::Mat& mask,
                              cv::Mat* gradient = nullptr,
                              const cv::Mat& clique_weights = cv::Mat());

/// The weight w_c of each clique of `size`×`size` filters, at its centre, given a guide image
/// (CV_32FC3, a registered colour image): the least guide_affinity(guide(centre), guide(tap),
/// sigma) over its taps (harmonic.h), so that a clique across an edge of the guide counts little
/// in E, as a colorization weight does across a colour edge. CV_64F of the guide's size; 1 where
/// the filter leaves the image. Throws InvalidInput on another type or a sigma not above 0.
cv::Mat foe_clique_weights(const cv::Mat& guide, int size, float sigma);

/// ∂²E/∂u² at x over the unknowns u, the pixels of `mask` (CV_8U, non-zero) in row-major order:
/// Σ_i α_i Σ_c ρ''(y_ic) J_ic J_icᵀ with ρ(y) = log(1 + y²/2). Positive definite at a strict local
/// minimum (what foe_map returns), not elsewhere.
Eigen::SparseMatrix<double> foe_hessian_of_unknowns(const FoeModel& model, const cv::Mat& x,
                                                    const cv::Mat& mask);

/// J ⋆ x (correlation, kernel CV_64F of odd size) at the pixels where the kernel lies inside x,
/// 0 elsewhere. Plain loops: the same value at any thread count, unlike cv::filter2D.
cv::Mat foe_response(const cv::Mat& x, const cv::Mat& kernel);

/// Jᵀ z, the adjoint of foe_response (z read where the kernel lies inside it).
cv::Mat foe_adjoint(const cv::Mat& z, const cv::Mat& kernel);

}  // namespace rangefill
