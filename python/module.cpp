// The Python module `rangefill` (python/rangefill/__init__.py re-exports it): depth maps and the
// inpainting back-ends on numpy arrays, meshes whose elements are numpy views, repair with the
// report of `rangefill repair --json` as a dict. The GIL is released during every long call.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstring>
#include <limits>
#include <optional>
#include <string>

#include "rangefill/core/errors.h"
#include "rangefill/core/topology.h"
#include "rangefill/depth/fill_depth.h"
#include "rangefill/hole/holes.h"
#include "rangefill/inpaint/inpainters.h"
#include "rangefill/io/depth_io.h"
#include "rangefill/io/mesh_io.h"
#include "rangefill/point_cloud/point_cloud.h"
#include "rangefill/repair/filler_options.h"
#include "rangefill/repair/pipeline.h"
#include "rangefill/reports/reports.h"

namespace py = pybind11;

namespace rangefill::python {

namespace {

// nlohmann::json as the Python value json.loads makes of it (dicts, lists, numbers, strings).
py::object to_python(const nlohmann::json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}

// "uint16", "float32", ... (">u2" for a byte order not the machine's)
std::string name_of(const py::dtype& dtype) {
  return py::str(static_cast<const py::handle&>(dtype)).cast<std::string>();
}

std::string shape_text(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) {
    text += (i ? ", " : "") + std::to_string(array.shape(i));
  }
  return text + (array.ndim() == 1 ? ",)" : ")");
}

// A cv::Mat of `type` over a 2-D array's pixels: the array's own buffer when its rows are
// contiguous (any row stride), else a C-contiguous copy held in `keep`. Throws InvalidInput
// naming `what` for another dimension count or element type than `dtype`.
cv::Mat image_over(const py::array& array, const py::dtype& dtype, int type, const char* what,
                   py::array& keep) {
  if (array.ndim() != 2) {
    throw InvalidInput(std::string(what) + ": a 2-D array expected, got shape " +
                       shape_text(array));
  }
  if (!array.dtype().is(dtype)) {
    throw InvalidInput(std::string(what) + ": " + name_of(dtype) + " expected, got " +
                       name_of(array.dtype()));
  }
  keep = array;
  const auto item = static_cast<py::ssize_t>(array.itemsize());
  if (array.strides(1) != item || array.strides(0) < array.shape(1) * item) {
    keep = py::array::ensure(array, py::array::c_style);
  }
  return cv::Mat(static_cast<int>(keep.shape(0)), static_cast<int>(keep.shape(1)), type,
                 const_cast<void*>(keep.data()), static_cast<size_t>(keep.strides(0)));
}

// An array over `image`'s pixels, which it keeps alive (no copy).
py::array array_of(cv::Mat image) {
  py::dtype dtype;
  switch (image.type()) {
    case CV_8UC1:
      dtype = py::dtype::of<uint8_t>();
      break;
    case CV_16UC1:
      dtype = py::dtype::of<uint16_t>();
      break;
    case CV_32FC1:
      dtype = py::dtype::of<float>();
      break;
    case CV_8UC3:
      dtype = py::dtype::of<uint8_t>();
      break;
    default:
      throw ProcessingError("an image of OpenCV type " + std::to_string(image.type()));
  }
  auto* owner = new cv::Mat(std::move(image));
  const py::capsule free(owner, [](void* mat) { delete static_cast<cv::Mat*>(mat); });
  const auto row = static_cast<py::ssize_t>(owner->step[0]);
  const auto pixel = static_cast<py::ssize_t>(owner->elemSize());
  if (owner->channels() == 3) {
    return py::array(dtype, {owner->rows, owner->cols, 3}, {row, pixel, py::ssize_t{1}},
                     owner->data, free);
  }
  return py::array(dtype, {owner->rows, owner->cols}, {row, pixel}, owner->data, free);
}

// A depth map's type: uint16 (millimetres) or float32 (metres).
int depth_type(const py::array& depth) {
  if (depth.dtype().is(py::dtype::of<uint16_t>())) return CV_16UC1;
  if (depth.dtype().is(py::dtype::of<float>())) return CV_32FC1;
  throw InvalidInput("depth: uint16 (millimetres) or float32 (metres) expected, got " +
                     name_of(depth.dtype()));
}

// A mask (bool or uint8, non-zero to fill) over its array, as CV_8UC1.
cv::Mat mask_over(const py::array& mask, py::array& keep) {
  const py::dtype dtype =
      mask.dtype().is(py::dtype::of<bool>()) ? py::dtype::of<bool>() : py::dtype::of<uint8_t>();
  return image_over(mask, dtype, CV_8UC1, "mask (bool or uint8)", keep);
}

// A colour image (H×W×3 uint8 in any channel order, or H×W uint8 grey) over its array, as
// CV_8UC3 or CV_8UC1 (the affinities of fill_depth do not depend on the channels' order).
cv::Mat color_over(const py::array& color, py::array& keep) {
  if (!color.dtype().is(py::dtype::of<uint8_t>()) ||
      !(color.ndim() == 2 || (color.ndim() == 3 && color.shape(2) == 3))) {
    throw InvalidInput("color: an H×W×3 or H×W uint8 array expected, got " +
                       name_of(color.dtype()) + " of " + std::to_string(color.ndim()) +
                       " dimensions");
  }
  keep = py::array::ensure(color, py::array::c_style);
  return cv::Mat(static_cast<int>(keep.shape(0)), static_cast<int>(keep.shape(1)),
                 keep.ndim() == 3 ? CV_8UC3 : CV_8UC1, const_cast<void*>(keep.data()));
}

// ---------------------------------------------------------------------------------------------
// Depth maps and back-ends

py::tuple fill_depth_array(const py::array& depth, const std::optional<py::array>& mask,
                           const std::optional<py::array>& color, DepthFillOptions options) {
  py::array depth_keep, mask_keep, color_keep;
  const int type = depth_type(depth);
  const cv::Mat image = image_over(depth, depth.dtype(), type, "depth", depth_keep);
  const cv::Mat invalid = mask ? mask_over(*mask, mask_keep) : cv::Mat();
  if (color) options.color = color_over(*color, color_keep);
  cv::Mat filled;
  DepthFillStats stats;
  {
    const py::gil_scoped_release release;
    stats = fill_depth(image, invalid, filled, options);
  }
  py::dict report = to_python(reports::depth_fill_report(stats));
  report["filled_mask"] = array_of(stats.filled_mask);
  return py::make_tuple(array_of(filled), report);
}

py::array inpaint_array(const py::array& image, const py::array& mask, const std::string& backend,
                        const InpainterOptions& options) {
  py::array image_keep, mask_keep;
  const cv::Mat depth = image_over(image, py::dtype::of<float>(), CV_32FC1, "image", image_keep);
  const cv::Mat masked = mask_over(mask, mask_keep);
  const std::unique_ptr<Inpainter> inpainter = make_inpainter(backend, options);
  cv::Mat out;
  {
    const py::gil_scoped_release release;
    inpainter->inpaint(depth, masked, out);
  }
  return array_of(out);
}

py::array read_depth(const std::filesystem::path& path) {
  cv::Mat depth;
  {
    const py::gil_scoped_release release;
    depth = read_depth_image(path);
  }
  return array_of(depth);
}

py::array read_color(const std::filesystem::path& path) {
  cv::Mat color;
  {
    const py::gil_scoped_release release;
    color = read_color_image(path);
  }
  return array_of(color);
}

void write_depth(const py::array& depth, const std::filesystem::path& path) {
  py::array keep;
  const cv::Mat image = image_over(depth, depth.dtype(), depth_type(depth), "depth", keep);
  const py::gil_scoped_release release;
  write_depth_image(image, path);
}

// ---------------------------------------------------------------------------------------------
// Meshes

// A view of `count` rows of `columns` values of T starting at `data`, kept alive by `owner`.
template <typename T>
py::array view(const py::handle& owner, const void* data, size_t count, size_t columns) {
  if (count == 0)
    return py::array_t<T>(columns == 1 ? std::vector<size_t>{0} : std::vector<size_t>{0, columns});
  if (columns == 1) {
    return py::array_t<T>({count}, {sizeof(T)}, static_cast<const T*>(data), owner);
  }
  return py::array_t<T>({count, columns}, {columns * sizeof(T), sizeof(T)},
                        static_cast<const T*>(data), owner);
}

// `values` (an N×3 array or what numpy makes one of, convertible to T) as N rows of three T;
// throws InvalidInput naming `what` otherwise.
template <typename Row, typename T>
std::vector<Row> rows_of(const py::handle& values, const char* what) {
  const auto array = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(values);
  if (!array || array.ndim() != 2 || array.shape(1) != 3) {
    PyErr_Clear();
    throw InvalidInput(std::string(what) + ": an N×3 array expected" +
                       (array ? ", got shape " + shape_text(array) : ""));
  }
  std::vector<Row> rows(static_cast<size_t>(array.shape(0)));
  if (!rows.empty()) std::memcpy(rows.data()->data(), array.data(), rows.size() * sizeof(Row));
  return rows;
}

Mesh make_python_mesh(const py::object& vertices, const py::object& faces,
                      const std::optional<py::object>& colors,
                      const std::optional<py::object>& normals) {
  const py::array indices = py::array::ensure(faces);
  const char kind = indices ? indices.dtype().kind() : '?';
  if (indices && indices.size() > 0 && kind != 'i' && kind != 'u') {
    throw InvalidInput("faces: integer vertex indices expected, got " + name_of(indices.dtype()));
  }
  // Indices beyond int32 would wrap round to valid ones when cast.
  if (indices && indices.size() > 0 &&
      (indices.attr("max")().cast<double>() > std::numeric_limits<int>::max() ||
       indices.attr("min")().cast<double>() < 0)) {
    throw InvalidInput("faces: vertex indices must lie in [0, 2^31)");
  }
  Mesh mesh = make_mesh(rows_of<Vec3, double>(vertices, "vertices"),
                        rows_of<Triangle, int>(faces, "faces"));
  if (colors) mesh.colors = rows_of<Rgb, float>(*colors, "colors");
  if (normals) mesh.normals = rows_of<Vec3, double>(*normals, "normals");
  validate_mesh(mesh, "mesh");
  return mesh;
}

py::tuple repair_mesh(const Mesh& mesh, const RepairOptions& options, const std::string& mesher) {
  validate_mesh(mesh, "mesh");
  RepairResult result;
  {
    const py::gil_scoped_release release;
    if (mesh.triangles.empty()) {
      if (mesher_from_name(mesher) == Mesher::none) {
        throw InvalidInput("mesh: a point cloud without faces (mesher='greedy' meshes it)");
      }
      result = repair(mesh_point_cloud(mesh), options);
    } else {
      result = repair(mesh, options);
    }
  }
  py::dict report = to_python(reports::repair_report(result));
  return py::make_tuple(py::cast(std::move(result.mesh)), report);
}

py::dict holes_of(const Mesh& mesh, bool vertices) {
  validate_mesh(mesh, "mesh");
  nlohmann::json report;
  {
    const py::gil_scoped_release release;
    const MeshTopology topology = build_topology(mesh);
    report = reports::holes_report(mesh, topology, find_holes(mesh, topology), vertices);
  }
  return to_python(report);
}

void register_errors(py::module_& module) {
  static py::exception<ProcessingError> processing(module, "ProcessingError", PyExc_RuntimeError);
  // pybind11 takes the translator as void (*)(std::exception_ptr): by value.
  py::register_exception_translator(
      [](std::exception_ptr error) {  // NOLINT(performance-unnecessary-value-param)
        try {
          if (error) std::rethrow_exception(error);
        } catch (const InvalidInput& e) {
          PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const IoError& e) {
          PyErr_SetString(PyExc_OSError, e.what());
        } catch (const ProcessingError& e) {
          PyErr_SetString(processing.ptr(), e.what());
        } catch (const Error& e) {
          PyErr_SetString(PyExc_RuntimeError, e.what());
        }
      });
}

// `options` with the radius (telea, ns) and foe's inference settings of a call.
InpainterOptions with_inference(InpainterOptions options, double radius,
                                const std::string& foe_start, double foe_tolerance,
                                int foe_iterations) {
  options.opencv.radius = radius;
  options.foe.start = foe_start;
  options.foe.tolerance = foe_tolerance;
  options.foe.iterations = foe_iterations;
  return options;
}

void add_depth_functions(py::module_& module) {
  const DepthFillOptions depth;
  const InpainterOptions& inpainting = depth.inpainting;
  module.def(
      "fill_depth",
      [](const py::array& image, const std::optional<py::array>& mask,
         const std::optional<py::array>& color, const std::string& inpainter, bool fast,
         int threads, long long backend_max_pixels, long long max_hole_pixels, bool keep_border,
         int reach, double discontinuity, const std::string& trend, double trend_ring, int margin,
         double radius, const std::string& foe_start, double foe_tolerance, int foe_iterations) {
        DepthFillOptions options;
        options.inpainter = inpainter;
        options.fast = fast;
        options.threads = threads;
        options.backend_max_pixels = backend_max_pixels;
        options.max_hole_pixels = max_hole_pixels;
        options.keep_border = keep_border;
        options.reach = reach;
        options.discontinuity = discontinuity;
        options.trend = trend_from_name(trend);
        options.trend_ring = trend_ring;
        options.margin = margin;
        options.inpainting =
            with_inference(options.inpainting, radius, foe_start, foe_tolerance, foe_iterations);
        return fill_depth_array(image, mask, color, options);
      },
      py::arg("depth"), py::arg("mask") = py::none(), py::kw_only(), py::arg("color") = py::none(),
      py::arg("inpainter") = depth.inpainter, py::arg("fast") = depth.fast,
      py::arg("threads") = depth.threads, py::arg("backend_max_pixels") = depth.backend_max_pixels,
      py::arg("max_hole_pixels") = depth.max_hole_pixels,
      py::arg("keep_border") = depth.keep_border, py::arg("reach") = depth.reach,
      py::arg("discontinuity") = depth.discontinuity, py::arg("trend") = trend_name(depth.trend),
      py::arg("trend_ring") = depth.trend_ring, py::arg("margin") = depth.margin,
      py::arg("radius") = inpainting.opencv.radius, py::arg("foe_start") = inpainting.foe.start,
      py::arg("foe_tolerance") = inpainting.foe.tolerance,
      py::arg("foe_iterations") = inpainting.foe.iterations,
      R"(Fills the holes of a depth map; returns (filled, stats).

depth: H×W uint16 (millimetres, 0 invalid) or float32 (metres, 0 or NaN invalid), any strides.
mask: H×W bool or uint8, the pixels to fill (non-zero); None fills every invalid pixel.
color: H×W×3 uint8 (RGB or BGR) or H×W uint8 grey, registered to the depth, or None: `rangefill
depth --color`.
The options and their defaults are `rangefill depth`'s (docs/depth.md): inpainter, the
back-end (backends()) for holes of up to backend_max_pixels, larger ones along lines, or 'lines'
for every hole; fast, fill along lines without looking for occluding edges hole by
hole (a few ms a VGA frame); threads, holes filled at once (every hardware thread; the result does not depend on
it); max_hole_pixels, larger holes left (0: no limit); keep_border, leave holes touching the
border; reach (pixels); discontinuity, relative depth jump between surfaces; trend, 'none',
'plane' or 'quadric'; trend_ring and margin (pixels); radius (pixels, telea and ns);
foe_start, foe_tolerance, foe_iterations (foe's inference).
filled: an array of depth's type and shape, every pixel outside the filled holes as given, bit
for bit the output of `rangefill depth`. stats: the dict of `rangefill depth --json` (holes,
filled, filled_pixels, at_edge, left_holes, left_pixels, left) and filled_mask, H×W uint8, 255
where a pixel was filled. Raises ValueError on a bad type, shape or option.)");
  module.def(
      "inpaint",
      [](const py::array& image, const py::array& mask, const std::string& backend, double radius,
         const std::string& model, double mls_alpha, double mls_ring, const std::string& foe_start,
         double foe_tolerance, int foe_iterations) {
        InpainterOptions options =
            with_inference({}, radius, foe_start, foe_tolerance, foe_iterations);
        options.foe.model = model;
        options.mls.alpha = mls_alpha;
        options.mls.ring = mls_ring;
        return inpaint_array(image, mask, backend, options);
      },
      py::arg("image"), py::arg("mask"), py::arg("backend"), py::kw_only(),
      py::arg("radius") = InpainterOptions{}.opencv.radius,
      py::arg("model") = InpainterOptions{}.foe.model,
      py::arg("mls_alpha") = InpainterOptions{}.mls.alpha,
      py::arg("mls_ring") = InpainterOptions{}.mls.ring,
      py::arg("foe_start") = InpainterOptions{}.foe.start,
      py::arg("foe_tolerance") = InpainterOptions{}.foe.tolerance,
      py::arg("foe_iterations") = InpainterOptions{}.foe.iterations,
      R"(Restores the masked pixels of an image with one back-end, like cv2.inpaint.

image: H×W float32, any strides; every pixel outside the mask is data. mask: H×W bool or uint8,
non-zero where to restore. backend: a name of backends(), or 'foe:MODEL'. Options: radius
(pixels; telea, ns), model (foe), mls_alpha (per squared pixel) and mls_ring (pixels) for mls,
foe_start, foe_tolerance, foe_iterations. Returns an H×W float32 array equal to image outside the
mask. Raises ValueError on an unknown back-end or a bad array.)");
  module.def("backends", &inpainter_names, "The names of the inpainting back-ends.");
  module.def("read_depth", &read_depth, py::arg("path"),
             R"(Reads a depth image: 16-bit PNG or TIFF as H×W uint16 (millimetres), float TIFF or
EXR as H×W float32 (metres). Raises OSError when the file cannot be read, ValueError when it is
not such an image.)");
  module.def("read_color", &read_color, py::arg("path"),
             R"(Reads the colour image that guides fill_depth: PNG, TIFF or JPEG, as H×W×3 uint8
(BGR, as OpenCV) or H×W uint8 (grey). Raises OSError or ValueError, as read_depth.)");
  module.def("write_depth", &write_depth, py::arg("depth"), py::arg("path"),
             R"(Writes a depth image atomically, in the format of the extension: uint16 to .png or
.tif/.tiff, float32 to .tif/.tiff or .exr. Raises ValueError or OSError.)");
}

// The read-only property `name` of the Mesh class: its vector `member` viewed as rows of `columns`
// values of T.
template <auto member, typename T, size_t columns>
void add_view(py::class_<Mesh>& mesh_class, const char* name) {
  mesh_class.def_property_readonly(name, [](const py::object& self) {
    const auto& values = self.cast<const Mesh&>().*member;
    return view<T>(self, values.data(), values.size(), columns);
  });
}

void add_mesh_class(py::module_& module) {
  py::class_<Mesh> mesh_class(module, "Mesh",
                              R"(A triangle mesh. Its arrays are views of the mesh's own memory
(no copy): change their values in place; a mesh of other sizes is a new Mesh.)");
  mesh_class
      .def(py::init(&make_python_mesh), py::arg("vertices"), py::arg("faces"),
           py::arg("colors") = py::none(), py::arg("normals") = py::none(),
           R"(vertices: N×3 positions; faces: M×3 vertex indices (counter-clockwise seen from
outside); colors: N×3 RGB in [0, 1]; normals: N×3. Raises ValueError on an index out of range, a
repeated index in a face or a non-finite coordinate.)")
      .def("__repr__", [](const Mesh& mesh) {
        return "rangefill.Mesh(vertices=" + std::to_string(mesh.vertex_count()) +
               ", faces=" + std::to_string(mesh.face_count()) +
               (mesh.has_colors() ? ", colors" : "") + (mesh.has_normals() ? ", normals" : "") +
               ")";
      });
  add_view<&Mesh::positions, double, 3>(mesh_class, "vertices");
  add_view<&Mesh::triangles, int32_t, 3>(mesh_class, "faces");
  add_view<&Mesh::colors, float, 3>(mesh_class, "colors");
  add_view<&Mesh::normals, double, 3>(mesh_class, "normals");
  add_view<&Mesh::vertex_hole, int32_t, 1>(mesh_class, "vertex_hole");
  add_view<&Mesh::face_hole, int32_t, 1>(mesh_class, "face_hole");
}

void add_mesh_functions(py::module_& module) {
  module.def(
      "read_mesh",
      [](const std::filesystem::path& path) {
        ReadResult read;
        {
          const py::gil_scoped_release release;
          read = rangefill::read_mesh(path);
        }
        for (const std::string& warning : read.warnings) {
          if (PyErr_WarnEx(PyExc_UserWarning, (path.string() + ": " + warning).c_str(), 1) < 0) {
            throw py::error_already_set();
          }
        }
        return read.mesh;
      },
      py::arg("path"),
      R"(Reads a mesh (.ply, .obj, .off, .stl); polygons are triangulated with a UserWarning.
Raises OSError when the file cannot be read, ValueError when it is malformed.)");
  module.def(
      "write_mesh",
      [](const Mesh& mesh, const std::filesystem::path& path, bool ascii, bool provenance) {
        validate_mesh(mesh, "mesh");
        WriteOptions options;
        options.encoding = ascii ? Encoding::ascii : Encoding::binary;
        options.provenance = provenance;
        const py::gil_scoped_release release;
        rangefill::write_mesh(mesh, path, options);
      },
      py::arg("mesh"), py::arg("path"), py::kw_only(), py::arg("ascii") = false,
      py::arg("provenance") = true,
      R"(Writes a mesh atomically in the format of the extension, in the types it was read
(binary unless ascii; PLY carries the provenance unless provenance=False). Raises ValueError or
OSError.)");
  const RepairOptions repair;
  const FillerOptions fillers;
  module.def("filler_names", &filler_names,
             "The fillers' names (filler, fallback and select take them; fairing:c0|c1|c2 and "
             "plane:BACKEND name variants).");
  module.def(
      "repair",
      [](const Mesh& mesh, const std::string& filler, const std::string& fallback,
         const std::string& select, const std::string& inpainter, const std::string& trend,
         const std::optional<std::vector<int>>& holes, bool fill_all, double border_share,
         int max_hole_size, double max_hole_area, int passes, int threads, double beta,
         double gamma, int rings, double radius, double alpha, const std::string& mesher) {
        FillerOptions fillers;
        fillers.plane.inpainter = inpainter;
        fillers.plane.trend = trend_from_name(trend);
        fillers.plane.image.beta = beta;
        fillers.plane.inpainting.opencv.radius = radius;
        fillers.plane.inpainting.mls.alpha = alpha;
        make_inpainter(inpainter, fillers.plane.inpainting);  // an unknown name fails first
        RepairOptions options;
        options.chain = make_filler_chain(filler, fallback, fillers);
        options.selection.candidates = make_fillers(select, fillers);
        if (holes) options.holes = *holes;
        options.border_share = fill_all ? 0 : border_share;
        options.max_hole_edges = max_hole_size;
        options.max_hole_area = max_hole_area;
        options.passes = passes;
        options.threads = threads;
        options.zone.gamma_degrees = gamma;
        options.zone.rings = rings;
        return repair_mesh(mesh, options, mesher);
      },
      py::arg("mesh"), py::kw_only(), py::arg("filler") = kDefaultFiller,
      py::arg("fallback") = kDefaultFallbacks, py::arg("select") = kDefaultCandidates,
      py::arg("inpainter") = fillers.plane.inpainter,
      py::arg("trend") = trend_name(fillers.plane.trend), py::arg("holes") = py::none(),
      py::arg("fill_all") = false, py::arg("border_share") = repair.border_share,
      py::arg("max_hole_size") = repair.max_hole_edges,
      py::arg("max_hole_area") = repair.max_hole_area, py::arg("passes") = repair.passes,
      py::arg("threads") = repair.threads, py::arg("beta") = fillers.plane.image.beta,
      py::arg("gamma") = repair.zone.gamma_degrees, py::arg("rings") = repair.zone.rings,
      py::arg("radius") = fillers.plane.inpainting.opencv.radius,
      py::arg("alpha") = fillers.plane.inpainting.mls.alpha, py::arg("mesher") = "greedy",
      R"(Fills the holes of a mesh; returns (repaired, report).

The options and their defaults are `rangefill repair`'s (docs/repair.md): filler and fallback
(the fill chain), select (the band test's candidates, or "none"), inpainter, trend, holes (loop ids of holes(); None: every loop but borders), fill_all,
border_share, max_hole_size (edges), max_hole_area (the mesh's units squared), passes, threads
(every hardware thread; the result does not depend on it), beta (grid step in mean edge
lengths), gamma (degrees), rings, radius (pixels), alpha (mls), mesher ('greedy' meshes a point
cloud first, 'none' refuses it).
repaired: a new Mesh, the input's vertices and faces first and bit for bit, vertex_hole and
face_hole the id of the hole that made each new element (-1: original). report: the dict of
`rangefill repair --json` (holes, open_loops, restoration_matrix, defects). A hole that cannot be
filled is reported and left open. Raises ValueError on an invalid mesh or option.)");
  module.def("holes", &holes_of, py::arg("mesh"), py::kw_only(), py::arg("vertices") = false,
             R"(The boundary loops of a mesh: the dict of `rangefill holes --json` (loops with id,
edges, perimeter, area, component, area_share, border, and their vertex ids with vertices=True;
mean_edge_length; the topology's defects).)");
}

}  // namespace

}  // namespace rangefill::python

PYBIND11_MODULE(_rangefill, module) {
  using namespace rangefill::python;
  module.doc() = "rangefill's C++ library (see the rangefill package for the documentation)";
  module.attr("__version__") = RANGEFILL_VERSION;
  register_errors(module);
  add_depth_functions(module);
  add_mesh_class(module);
  add_mesh_functions(module);
}
