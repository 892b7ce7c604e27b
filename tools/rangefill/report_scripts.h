// The scripts report.html inlines, built into the binary: three.js and its OrbitControls (Debian's
// libjs-three, read when the build is configured) and the report's own, report.js.
#pragma once

namespace rangefill::cli {

extern const char* const kThreeJs;
extern const char* const kOrbitControlsJs;
extern const char* const kReportJs;

}  // namespace rangefill::cli
