// idbench.render: the robot at instants of a motion as one labelled figure,
// a numpy image (and a PNG file when asked).
#include <algorithm>
#include <cstdint>
#include <memory>
#include <stdexcept>

#include "bindings.h"
#include "idbench/render/png_codec.h"
#include "idbench/workbench/commands/render_command.h"
#include "idbench/workbench/formats/atomic_file.h"

namespace idbench::python {

void BindRender(py::module_& m) {
  const RenderOptions render_defaults;
  m.def(
      "render",
      [](const Robot& robot, const std::string& trajectory, const std::vector<double>& times, double duration,
         double paper_accel, const std::string& layout, const std::string& size, const std::string& png) {
        RenderOptions options;
        options.robot = robot.source;
        options.trajectory = trajectory;
        if (!times.empty()) options.times = times;
        options.duration = duration;
        options.paper_accel_deg_s2 = paper_accel;
        options.layout = layout;
        options.size = size;
        std::string why;
        if (!options.IsValid(&why)) throw std::invalid_argument(why);
        const std::unique_ptr<Trajectory> motion = MakeRenderTrajectory(*robot.model, options);
        const PoseFigureOptions figure = options.figure(motion->duration());
        if (!figure.IsValid(motion->duration(), &why)) throw std::invalid_argument(why);
        Image image;
        {
          py::gil_scoped_release release;
          image = RenderPoseFigureImage(*robot.model, *motion, figure);
        }
        if (!png.empty()) WriteFileAtomically(png, EncodePng(image));
        py::array_t<std::uint8_t> pixels({image.height, image.width, 3});
        std::copy(image.rgb.begin(), image.rgb.end(), pixels.mutable_data());
        return pixels;
      },
      py::arg("robot"), py::arg("trajectory") = render_defaults.trajectory, py::kw_only(),
      py::arg("times") = std::vector<double>{}, py::arg("duration") = render_defaults.duration,
      py::arg("paper_accel") = render_defaults.paper_accel_deg_s2, py::arg("layout") = render_defaults.layout,
      py::arg("size") = render_defaults.size, py::arg("png") = std::string(),
      "Renders the robot at instants of a motion as one labelled figure (as `idbench render`, headless); "
      "returns it as a height × width × 3 uint8 array and writes it as PNG when png names a file");
}

}  // namespace idbench::python
