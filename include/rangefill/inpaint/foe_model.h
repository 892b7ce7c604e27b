// Fields-of-Experts models (Roth & Black): the prior behind the "foe" back-end (filters/foe.h). The
// image x is scored by E(x) = Σ_i α_i Σ_c log(1 + ½ (s·J_i ⋆ x)_c²) over the cliques c where the
// s×s filter J_i lies inside the image (⋆: correlation, s: the model's input scale); the masked
// pixels are the unknowns, the others stay fixed.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <Eigen/SparseCore>
#include <opencv2/core.hpp>

namespace rangefill {

/// A fitted FoE model. Written and read as OpenCV FileStorage YAML (see models/README.md); Roth &
/// Black's ASCII `.foe` files are read too.
struct FoeModel {
  static constexpr int kFormatVersion = 1;
  std::string name;
  int size = 3;                  // filters are size × size, size odd
  std::vector<cv::Mat> filters;  // CV_64F correlation kernels, one per expert
  std::vector<double> alphas;    // α_i > 0
  double input_scale = 1;        // the model sees input_scale · x / divisor, where the divisor is
  bool known_rms = false;        // the RMS of the known pixels when set, else 1
  std::string normalisation;     // what x is expected to be
  std::string training;          // what data and loss fitted it, and the command

  int count() const { return static_cast<int>(filters.size()); }
};

/// Parses a model from YAML text or from Roth & Black's `.foe` format (told apart by content);
/// `name` names it in messages. Throws InvalidInput on malformed text.
FoeModel parse_foe_model(std::string_view text, const std::string& name);

/// The YAML text of a model (parse_foe_model reads it back exactly: numbers in shortest round-trip
/// form).
std::string serialize_foe_model(const FoeModel& model);

/// A model shipped with the library, by name: "depth" (fitted on depth patches by
/// `rangefill train-foe`), "roth-black" (Roth & Black's 5×5 natural-image filters, scaled to
/// inputs in [0, 1]); or a model file's path. Throws InvalidInput otherwise.
FoeModel load_foe_model(const std::string& name_or_path);

/// The names load_foe_model knows without a path.
std::vector<std::string> shipped_foe_models();

/// The divisor of the model's inputs for an image (any type) and its mask (CV_8U, 255 = unknown):
/// the RMS of the known pixels when model.known_rms (1 if they are all 0), else 1.
double foe_input_divisor(const FoeModel& model, const cv::Mat& image, const cv::Mat& mask);

/// E(x) for x CV_64F (already divided by foe_input_divisor); when `gradient` is given it receives
/// ∇E (CV_64F, the size of x): Σ_i s·J_iᵀ ψ_i(y_i), ψ_i(y) = α_i y / (1 + y²/2), y_i = s·J_i ⋆ x.
/// The same value at any thread count.
double foe_energy(const FoeModel& model, const cv::Mat& x, cv::Mat* gradient = nullptr);

/// E(x) up to a constant of the unmasked pixels: the sum over the cliques that cover a pixel of
/// `mask` (CV_8U, non-zero = unknown) only, which is all that inference needs; ∇E is exact at the
/// masked pixels.
double foe_energy_of_unknowns(const FoeModel& model, const cv::Mat& x, const cv::Mat& mask,
                              cv::Mat* gradient = nullptr);

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
///    the Gaussian field with the model's filters (spread ~6 against ~44 for L alone on the
///    shipped models); (L + tL²)⁻¹ = (I + tL)⁻¹L⁻¹ is one sparse 5-point factorisation and a
///    Chebyshev polynomial in the well-conditioned I + tL. Backtracking (Armijo) line
///    search; E and ∇E by blocked single-precision matrix products, summed in double.
///  - newton: steps x ← x − M⁻¹∇E, reusing each sparse Cholesky factorisation (CHOLMOD) while it
///    makes fast progress: M is first the matrix of the Gaussian field with the same filters and
///    weights (log(1 + y²/2) replaced by y²/2), a quadratic upper bound of E everywhere; when
///    progress slows, the Hessian of E where it is positive definite (Newton), else the
///    half-quadratic bound of Geman & Yang at the current point. Every step lowers E.
cv::Mat foe_map(const FoeModel& model, const cv::Mat& image, const cv::Mat& mask,
                const FoeMapOptions& options = {});

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
