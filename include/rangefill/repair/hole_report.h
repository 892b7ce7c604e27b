// What happened to one hole of a repair: the refusals met, the band tests, what filled it and
// the seconds of each step.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rangefill/hole/fill.h"
#include "rangefill/hole/filler.h"

namespace rangefill {

/// One refusal met on the way: of a filler, or (filler empty) of the hole before any.
struct Attempt {
  std::string filler;  // its name (fillers.h)
  std::string method;  // Filler::method
  Refused refused;
};

/// One candidate filler's band test (selection.h).
struct CandidateScore {
  std::string candidate;
  std::optional<double> score;  // RMS distance to the hidden band over d_m; none when refused
  double seconds = 0;
};

struct HoleReport {
  int id = 0;    // unique over the run; the provenance of what it generated. In pass 0 it is the
                 // loop's id in the input (as `rangefill holes` lists them)
  int pass = 0;  // 0 for the input's holes, 1+ for holes found again after merging
  int loop = 0;  // id of the loop in its pass's HoleSet
  int boundary_vertices = 0;
  double area = 0;
  int rings = 0;       // ν
  int zone_faces = 0;  // of the zone; of the part the plane saw when a range image was made
  ImageFigures image;  // of the last range image made, if any
  int new_vertices = 0;
  int new_faces = 0;
  double seconds = 0;  // whole hole, band tests included
  /// Seconds by step, as the pipeline timed them: "zone", each filler tried (by name),
  /// "checking" (acceptance.h), and the fillers' own steps ("planes", "image", "inpainting",
  /// "stitching" of the image pipeline).
  std::vector<StepSeconds> steps;
  std::vector<int> other_holes;  // other loops the zone reached
  bool filled = false;
  std::string filler;                     // the name of the filler that filled it
  std::string method;                     // who filled it, for tables: the filler's method, or a
                                          // baseline's (baselines.h)
  std::vector<CandidateScore> selection;  // the band tests, when candidates were scored
  std::string selected;                   // the candidate that filled it, if one did
  std::vector<Attempt> attempts;          // every refusal, in the order met
  std::string failure;                    // when not filled: the refusals in one line
};

}  // namespace rangefill
