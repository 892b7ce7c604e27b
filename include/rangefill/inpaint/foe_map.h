// MAP inference under a Fields-of-Experts model (foe_energy.h): the unknown pixels that lower E
// from a start, by L-BFGS or Newton-type steps.
#pragma once

#include <opencv2/core.hpp>

#include "rangefill/inpaint/foe_model.h"

namespace rangefill {

enum class FoeMapMethod {
  lbfgs,   // fast: preconditioned L-BFGS in single precision, stops on the relative decrease of E
  newton,  // exact: Newton-type steps in double precision to a stationary point (training's
           // implicit gradient needs one)
};

struct FoeMapOptions {
  int max_iterations = 100;           // bound steps after the start
  double function_tolerance = 1e-6;   // stop when a step lowers E by less than this share of E
  double gradient_tolerance = 1e-10;  // or when max |∂E/∂x| over the unknowns falls below this
  FoeMapMethod method = FoeMapMethod::lbfgs;
  bool start_from_image = false;  // start from the unknowns' values in the image, not harmonic
};

/// The MAP estimate under `model` of the pixels of `image` (CV_64F, already divided by
/// foe_input_divisor) under `mask` (CV_8U, non-zero = unknown); the other pixels are returned
/// unchanged. Inference starts from the harmonic fill (Laplace's equation; within the known values
/// around each hole), or with options.start_from_image from the unknowns' values in `image`
/// (otherwise not read), and only lowers E from there: a local minimum near the start, as E is
/// not convex. Deterministic; a mask covering the whole image gives zeros (nothing to go by).
///  - lbfgs: L-BFGS whose initial inverse Hessian is (L + t·L²)⁻¹ scaled, L the 5-point Laplacian
///    over the unknowns: t is fitted to the model so that the polynomial follows the spectrum of
///    the Gaussian field with the model's filters far more closely than L alone does;
///    (L + tL²)⁻¹ = (I + tL)⁻¹L⁻¹ is one sparse 5-point factorisation and a
///    Chebyshev polynomial in the well-conditioned I + tL. Backtracking (Armijo) line
///    search; E and ∇E by blocked single-precision matrix products, summed in double.
///  - newton: steps x ← x − M⁻¹∇E, reusing each sparse Cholesky factorisation (CHOLMOD) while it
///    makes fast progress: M is first the matrix of the Gaussian field with the same filters and
///    weights (log(1 + y²/2) replaced by y²/2), a quadratic upper bound of E everywhere; when
///    progress slows, the Hessian of E where it is positive definite (Newton), else the
///    half-quadratic bound of Geman & Yang at the current point. Every step lowers E.
/// With `clique_weights` (CV_64F, the image's size, foe_clique_weights; empty for none), E is
/// Σ_i α_i Σ_c w_c log(1 + ½ y_ic²), w_c read at the clique's centre; lbfgs's preconditioner
/// stays that of the unweighted field, so weights far below 1 take it more steps.
cv::Mat foe_map(const FoeModel& model, const cv::Mat& image, const cv::Mat& mask,
                const FoeMapOptions& options = {}, const cv::Mat& clique_weights = cv::Mat());

}  // namespace rangefill
