// rover-stereo: runs the dl_stereo pipeline on a rectified pair of image files and writes the
// disparity as float (PFM or TIFF) plus a colour PNG for people; with a focal length and a
// baseline it also writes the range image.
//
//   rover-stereo --left L.png --right R.png --focal 700 --baseline 0.2
//                --disparity out.pfm --color out.png [--range range.tif] [options]
// or, for raw images with JPL camera models (PDS3 labels with CAHV/CAHVOR/CAHVORE):
//   rover-stereo --left L.png --right R.png --left-model L.LBL --right-model R.LBL
//                --disparity out.pfm --range range.tif
#include <CLI/CLI.hpp>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <string>

#include "rover/dl/stereo/disparity_io.hpp"
#include "rover/dl/stereo/pipeline.hpp"
#ifdef ROVER_STEREO_HAVE_GEOMETRY
#include "rover/dl/stereo/geometry_adapter.hpp"
#include "rover/geometry/pds_label.hpp"
#endif

namespace st = rover::dl::stereo;

namespace {

int Fail(const rover::Status& s) {
  std::fprintf(stderr, "rover-stereo: %s\n", s.ToString().c_str());
  return s.code() == rover::StatusCode::kNotFound ? 3 : 2;
}

rover::Status CheckOutputPath(const std::string& option, const std::string& path) {
  if (path.empty()) return rover::Status::Ok();
  const auto parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty() && !std::filesystem::is_directory(parent, ec)) {
    return rover::NotFound(option + " '" + path + "': folder '" + parent.string() +
                           "' does not exist");
  }
  return rover::Status::Ok();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "rover-stereo: JPL/MER-style stereo ranging on a rectified image pair.\n"
      "Writes the disparity [px, at the pyramid level] as float PFM/TIFF (invalid = NaN in "
      "TIFF, +inf in PFM) and a colour PNG."};
  std::string left_path, right_path, disparity_path, color_path, range_path, status_path;
  std::string left_model_path, right_model_path;
  double focal = 0.0, baseline = 0.0, cx = -1.0, cy = -1.0, doffs = 0.0;
  st::StereoOptions o;
  std::string prefilter = st::PrefilterKindName(o.prefilter.kind);
  std::string subpixel = "parabola";
  bool no_lr = false, no_overhang = false, full_only = false;

  app.add_option("--left", left_path, "left rectified image (8/16-bit, grey or colour)")
      ->required();
  app.add_option("--right", right_path, "right rectified image")->required();
  app.add_option("--disparity", disparity_path, "output disparity, .pfm or .tif")->required();
  app.add_option("--color", color_path, "output colour PNG of the disparity");
  app.add_option("--range", range_path,
                 "output range [m], .pfm or .tif (needs --focal, --baseline)");
  app.add_option("--status", status_path, "output per-pixel status codes as 8-bit PNG");
  app.add_option("--left-model", left_model_path,
                 "PDS3 label with the left camera's CAHV/CAHVOR/CAHVORE model: the images are raw "
                 "and get rectified (needs --right-model)");
  app.add_option("--right-model", right_model_path, "PDS3 label of the right camera");
  app.add_option("--focal", focal, "focal length of the rectified pair [px, full resolution]");
  app.add_option("--baseline", baseline, "baseline [m]");
  app.add_option("--cx", cx, "left principal point column [px] (default: image centre)");
  app.add_option("--cy", cy, "left principal point row [px] (default: image centre)");
  app.add_option("--doffs", doffs, "cx_right - cx_left [px]")->capture_default_str();
  app.add_option("--min-disparity", o.correlator.min_disparity, "smallest disparity [px]")
      ->capture_default_str();
  app.add_option("--num-disparities", o.correlator.num_disparities, "search range size [px]")
      ->capture_default_str();
  app.add_option("--window", o.correlator.window, "SAD window (odd)")->capture_default_str();
  app.add_option("--levels", o.pyramid_levels, "pyramid levels (image halved per level)")
      ->capture_default_str();
  app.add_option("--prefilter", prefilter, "none, log or dog")->capture_default_str();
  app.add_option("--sigma", o.prefilter.sigma, "prefilter sigma [px]")->capture_default_str();
  app.add_option("--prefilter-gain", o.prefilter.gain, "prefilter gain")->capture_default_str();
  app.add_option("--gamma", o.gamma, "gamma correction (1 = off)")->capture_default_str();
  app.add_option("--white-level", o.white_level, "input value mapped to white (16-bit data)")
      ->capture_default_str();
  app.add_option("--uniqueness", o.correlator.uniqueness_ratio, "secondary-minimum margin")
      ->capture_default_str();
  app.add_option("--min-curvature", o.correlator.min_curvature, "flat-valley threshold")
      ->capture_default_str();
  app.add_option("--lr-max-diff", o.correlator.lr_max_diff, "left-right tolerance [px]")
      ->capture_default_str();
  app.add_flag("--no-lr", no_lr, "disable the left-right check");
  app.add_flag("--full-search-only", full_only, "reject pixels with a truncated search range");
  app.add_option("--blob-min-area", o.filters.blob_min_area, "blob filter area [px], 0 = off")
      ->capture_default_str();
  app.add_option("--border", o.filters.border_px, "extra border margin [px]")
      ->capture_default_str();
  app.add_flag("--no-overhang", no_overhang, "disable the overhang filter");
  app.add_option("--subpixel", subpixel, "none, parabola or equiangular")->capture_default_str();
  app.add_option("--threads", o.correlator.num_threads, "threads")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  for (const auto& [opt, path] :
       {std::pair<std::string, std::string>{"--disparity", disparity_path},
        {"--range", range_path}}) {
    if (path.empty()) continue;
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".pfm" && ext != ".tif" && ext != ".tiff") {
      return Fail(rover::InvalidArgument(opt + " '" + path + "' must end in .pfm, .tif or .tiff"));
    }
  }
  auto kind = st::ParsePrefilterKind(prefilter);
  if (!kind.ok()) return Fail(kind.status());
  o.prefilter.kind = *kind;
  if (subpixel == "none") {
    o.correlator.subpixel = st::SubpixelMethod::kNone;
  } else if (subpixel == "parabola") {
    o.correlator.subpixel = st::SubpixelMethod::kParabola;
  } else if (subpixel == "equiangular") {
    o.correlator.subpixel = st::SubpixelMethod::kEquiangular;
  } else {
    return Fail(rover::InvalidArgument("--subpixel '" + subpixel +
                                       "' is not one of: none, parabola, equiangular"));
  }
  if (no_lr) o.correlator.lr_max_diff = -1;
  if (no_overhang) o.filters.overhang = false;
  o.correlator.full_search_only = full_only;

  auto left = st::LoadGrayImage(left_path);
  if (!left.ok()) return Fail(left.status().WithPrefix("--left"));
  auto right = st::LoadGrayImage(right_path);
  if (!right.ok()) return Fail(right.status().WithPrefix("--right"));
  for (const auto& [opt, path] :
       {std::pair<std::string, std::string>{"--disparity", disparity_path},
        {"--color", color_path},
        {"--range", range_path},
        {"--status", status_path}}) {
    if (auto s = CheckOutputPath(opt, path); !s.ok()) return Fail(s);
  }

  std::optional<st::StereoCamera> camera;
#ifdef ROVER_STEREO_HAVE_GEOMETRY
  std::optional<st::StereoSetup> setup;
#endif
  if (!left_model_path.empty() || !right_model_path.empty()) {
    if (left_model_path.empty() || right_model_path.empty()) {
      return Fail(rover::InvalidArgument("--left-model and --right-model go together"));
    }
    if (focal != 0.0 || baseline != 0.0) {
      return Fail(rover::InvalidArgument(
          "give either camera models or --focal/--baseline, not both (the models define them)"));
    }
#ifdef ROVER_STEREO_HAVE_GEOMETRY
    std::optional<rover::geometry::CameraModel> models[2];
    const std::string paths[2] = {left_model_path, right_model_path};
    for (int i = 0; i < 2; ++i) {
      auto label = rover::geometry::ReadPdsCameraLabel(paths[i]);
      if (!label.ok())
        return Fail(label.status().WithPrefix(i == 0 ? "--left-model" : "--right-model"));
      // MSL/MER models live in ROVER_NAV_FRAME (x fwd, y right, z down): use the stack's rover
      // frame (x fwd, y left, z up) for range and points.
      models[i] = label->model_frame == "ROVER_NAV_FRAME"
                      ? rover::geometry::Transform(label->model, rover::geometry::RoverFromMslNav())
                      : label->model;
    }
    auto s = st::MakeStereoSetup(*models[0], *models[1]);
    if (!s.ok()) return Fail(s.status().WithPrefix("camera models"));
    setup = std::move(*s);
    camera = setup->camera;
#else
    return Fail(rover::Unavailable("camera models need core/geometry, which this build lacks"));
#endif
  } else if (focal != 0.0 || baseline != 0.0) {
    st::StereoCamera cam;
    cam.model.focal_px = focal;
    cam.model.baseline_m = baseline;
    cam.model.cx = cx >= 0.0 ? cx : 0.5 * (left->cols - 1);
    cam.model.cy = cy >= 0.0 ? cy : 0.5 * (left->rows - 1);
    cam.model.doffs_px = doffs;
    if (auto s = cam.Validate(); !s.ok()) return Fail(s.WithPrefix("--focal/--baseline"));
    camera = cam;
  } else if (!range_path.empty()) {
    return Fail(rover::InvalidArgument("--range needs --focal and --baseline or camera models"));
  }

  auto pipe = st::StereoPipeline::Create(o, camera);
  if (!pipe.ok()) return Fail(pipe.status());
  st::StereoInput in;
  in.left = *left;
  in.right = *right;
#ifdef ROVER_STEREO_HAVE_GEOMETRY
  if (setup.has_value()) in.rectification = &setup->maps;
#endif
  st::StereoOutput out;
  if (auto s = pipe->Process(in, &out); !s.ok()) return Fail(s);

  if (auto s = st::WriteFloatImage(disparity_path, out.disparity.disparity); !s.ok()) {
    return Fail(s.WithPrefix("--disparity"));
  }
  if (!color_path.empty()) {
    auto colour = st::ColorizeDisparity(out.disparity.disparity, o.correlator.min_disparity,
                                        o.correlator.min_disparity + o.correlator.num_disparities);
    if (!colour.ok()) return Fail(colour.status());
    if (!cv::imwrite(color_path, *colour)) {
      return Fail(rover::Unavailable("--color: cannot write '" + color_path + "'"));
    }
  }
  if (!status_path.empty() && !cv::imwrite(status_path, out.disparity.status)) {
    return Fail(rover::Unavailable("--status: cannot write '" + status_path + "'"));
  }
  if (!range_path.empty()) {
    if (auto s = st::WriteFloatImage(range_path, out.range); !s.ok()) {
      return Fail(s.WithPrefix("--range"));
    }
  }
  const int total = out.disparity.disparity.rows * out.disparity.disparity.cols;
  std::printf("rover-stereo: %dx%d at level %d, %d valid pixels (%.1f %%) in %.1f ms\n",
              out.disparity.disparity.cols, out.disparity.disparity.rows, out.level, out.counts[0],
              100.0 * out.counts[0] / total, out.timings.total_ms);
  std::printf("  rejected:");
  for (int i = 1; i < st::kNumPixelStatus; ++i) {
    if (out.counts[static_cast<std::size_t>(i)] > 0) {
      std::printf(" %s=%d", st::PixelStatusName(static_cast<st::PixelStatus>(i)),
                  out.counts[static_cast<std::size_t>(i)]);
    }
  }
  std::printf("\n");
  return 0;
}
