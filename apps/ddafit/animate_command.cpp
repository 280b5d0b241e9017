// ddafit animate DIR: the blocks of a finished run coloured by speed (the seed's Fig. 17),
// from the VTK snapshots `simulate --vtk-interval` wrote into DIR/vtk. One PNG per
// snapshot, PNGs at chosen times, and an animated GIF, all drawn by gnuplot with a colour
// bar in m/s and the time on each frame; an MP4 through ffmpeg when it is installed.
#include <fmt/format.h>
#include <fmt/os.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <system_error>

#include "forward/io/gnuplot.hpp"
#include "apps/ddafit/commands.hpp"
#include "apps/ddafit/exit_codes.hpp"
#include "forward/io/run_files.hpp"
#include "apps/ddafit/plots.hpp"
#include "apps/ddafit/vtk_reader.hpp"

namespace ddafit::app {
namespace {

namespace fs = std::filesystem;

// A perceptually even palette from dark (at rest) to bright (fastest), readable in grey.
constexpr const char* kPalette =
    "set palette defined (0 '#30123b', 0.2 '#4662d7', 0.4 '#1ae4b6', 0.6 '#a4fc3c', 0.8 '#fba238', 1 '#7a0403')\n";

std::vector<fs::path> snapshot_files(const fs::path& vtk_dir) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(vtk_dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("blocks_", 0) == 0 && entry.path().extension() == ".vtk") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Free blocks as closed polygons "x y speed", blank line between; fixed blocks apart.
void write_frame_data(const Snapshot& s, const fs::path& free_path, const fs::path& fixed_path) {
  auto free_out = fmt::output_file(free_path.string());
  auto fixed_out = fmt::output_file(fixed_path.string());
  for (size_t b = 0; b < s.polygons.size(); ++b) {
    auto& out = s.fixed[b] ? fixed_out : free_out;
    for (size_t k = 0; k <= s.polygons[b].size(); ++k) {
      const Vec2& p = s.points[static_cast<size_t>(s.polygons[b][k % s.polygons[b].size()])];
      out.print("{:.6f} {:.6f} {:.4g}\n", p.x(), p.y(), s.speed[b]);
    }
    out.print("\n");
  }
}

// The gnuplot commands that draw one frame (terminal and output set by the caller).
std::string frame_plot(const fs::path& free_path, const fs::path& fixed_path, double time, double line_width) {
  return fmt::format(
      "set title 't = {:.1f} s'\n"
      "plot '{}' using 1:2 with filledcurves closed fc rgb '#d9d9d9' notitle, "
      "'{}' using 1:2:3 with filledcurves closed fc palette notitle, "
      "'' using 1:2 with lines lc rgb '#404040' lw {} notitle\n",
      time, fixed_path.string(), free_path.string(), line_width);
}

// Frame index nearest to each requested time; an empty string or a one-line error.
std::string pick_frames(const std::vector<Snapshot>& frames, const std::vector<double>& times, std::vector<size_t>& out) {
  for (double t : times) {
    size_t best = 0;
    for (size_t k = 1; k < frames.size(); ++k)
      if (std::abs(frames[k].time - t) < std::abs(frames[best].time - t)) best = k;
    const double spacing = frames.size() > 1 ? (frames.back().time - frames.front().time) / (frames.size() - 1) : 0.0;
    if (!std::isfinite(t) || std::abs(frames[best].time - t) > 0.5 * spacing + 1e-9)
      return fmt::format("--times: no snapshot near t = {} s (the snapshots span {:.3g}-{:.3g} s)", t,
                         frames.front().time, frames.back().time);
    out.push_back(best);
  }
  return {};
}

}  // namespace

int run_animate(const AnimateArgs& args) {
  const fs::path dir(args.dir), vtk_dir = dir / "vtk";
  const std::vector<fs::path> files = snapshot_files(vtk_dir);
  if (files.empty()) {
    std::cerr << vtk_dir.string() << ": no snapshots (blocks_NNNNN.vtk); run simulate with --vtk-interval 0.5\n";
    return kExitBadInput;
  }
  std::vector<Snapshot> frames(files.size());
  for (size_t k = 0; k < files.size(); ++k) {
    if (const std::string problem = read_snapshot(files[k].string(), frames[k]); !problem.empty()) {
      std::cerr << problem << "\n";
      return kExitBadInput;
    }
  }
  std::vector<size_t> chosen;
  if (const std::string problem = pick_frames(frames, args.times, chosen); !problem.empty()) {
    std::cerr << "ddafit animate: " << problem << "\n";
    return kExitBadInput;
  }
  // One colour scale and one view for the whole run, so frames compare. The view is the
  // first snapshot's extent (the whole scene at the start): a block thrown far out of the
  // scene would otherwise shrink the slide to a corner of every frame.
  double top_speed = args.max_speed;
  if (args.max_speed <= 0.0)
    for (const Snapshot& s : frames)
      for (size_t b = 0; b < s.speed.size(); ++b)
        if (!s.fixed[b]) top_speed = std::max(top_speed, s.speed[b]);
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const Vec2& p : frames.front().points) {
    x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x());
    y0 = std::min(y0, p.y()), y1 = std::max(y1, p.y());
  }
  if (!(top_speed > 0.0)) top_speed = 1.0;
  top_speed = std::ceil(top_speed);

  const fs::path out = args.out.empty() ? dir / "animation" : fs::path(args.out);
  if (const std::string problem = io::prepare_output_folder(out.string()); !problem.empty()) {
    std::cerr << problem << "\n";
    return kExitBadInput;
  }
  std::error_code ec;
  const fs::path data = out / "data";
  fs::create_directories(data, ec);
  const double aspect = (y1 - y0) / std::max(x1 - x0, 1e-9);
  const int width = 1600, height = std::clamp(static_cast<int>(std::lround(width * aspect)) + 160, 400, 1400);
  // Outlines thin out with the block count, so that thousands of blocks keep their colour.
  const double line_width = frames.front().polygons.size() > 500 ? 0.1 : 0.5;
  const std::string common = fmt::format(
      "set size ratio -1\nset xrange [{}:{}]\nset yrange [{}:{}]\nset xlabel 'x (m)'\nset ylabel 'y (m)'\n"
      "set cbrange [0:{}]\nset cblabel 'block speed (m/s)'\n{}",
      x0, x1, y0, y1, top_speed, kPalette);
  try {
    auto png = fmt::output_file((out / "frames.gp").string());
    auto gif = fmt::output_file((out / "animation.gp").string());
    png.print("set terminal pngcairo size {},{} font ',12'\n{}", width, height, common);
    gif.print("set terminal gif animate delay {} size {},{} optimize\nset output '{}'\n{}",
              std::max(1, static_cast<int>(std::lround(100.0 / args.fps))), width / 2, height / 2,
              (out / "animation.gif").string(), common);
    for (size_t k = 0; k < frames.size(); ++k) {
      const fs::path free_path = data / fmt::format("free_{:05d}.dat", k);
      const fs::path fixed_path = data / fmt::format("fixed_{:05d}.dat", k);
      write_frame_data(frames[k], free_path, fixed_path);
      png.print("set output '{}'\n{}", (out / fmt::format("frame_{:05d}.png", k)).string(),
                frame_plot(free_path, fixed_path, frames[k].time, line_width));
      gif.print("{}", frame_plot(free_path, fixed_path, frames[k].time, line_width));
    }
    for (size_t k : chosen)
      png.print("set output '{}'\n{}", (out / fmt::format("speed_t{:05.1f}s.png", frames[k].time)).string(),
                frame_plot(data / fmt::format("free_{:05d}.dat", k), data / fmt::format("fixed_{:05d}.dat", k),
                           frames[k].time, line_width));
  } catch (const std::system_error& e) {
    std::cerr << out.string() << ": cannot write: " << e.what() << "\n";
    return kExitBadInput;
  }
  std::string reason;
  if (!io::run_gnuplot((out / "frames.gp").string(), "the data files", reason) ||
      !io::run_gnuplot((out / "animation.gp").string(), "the data files", reason)) {
    std::cerr << "ddafit animate: " << reason << "\n";
    return kExitRunFailed;
  }
  std::cout << "wrote " << frames.size() << " frames (t = " << frames.front().time << "-" << frames.back().time
            << " s, speed scale 0-" << top_speed << " m/s), " << chosen.size() << " chosen times and animation.gif in "
            << out.string() << "\n";
  if (args.mp4) {
    if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0) {
      std::cerr << "ddafit animate: --mp4 needs ffmpeg (apt-get install ffmpeg); the PNG frames and GIF are written\n";
      return kExitRunFailed;
    }
    const std::string cmd = fmt::format(
        "ffmpeg -y -loglevel error -framerate {} -i '{}' -vf 'scale=trunc(iw/2)*2:trunc(ih/2)*2' -c:v libx264 "
        "-pix_fmt yuv420p '{}'",
        args.fps, (out / "frame_%05d.png").string(), (out / "animation.mp4").string());
    if (std::system(cmd.c_str()) != 0) {
      std::cerr << "ddafit animate: ffmpeg failed to write animation.mp4\n";
      return kExitRunFailed;
    }
    std::cout << "wrote " << (out / "animation.mp4").string() << "\n";
  }
  return kExitSuccess;
}

}  // namespace ddafit::app
