#include "rover/dl/stereo/raw_stereo_pair.hpp"

namespace rover::dl::stereo {
namespace {

std::string SizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

}  // namespace

Status CheckRawStereoPair(const RawStereoPair& p) {
  if (p.width < 1 || p.height < 1) {
    return InvalidArgument("stereo frame size " + SizeText(p.width, p.height) + " is empty");
  }
  if (p.stamp.ns <= 0) {
    return InvalidArgument("stereo frame stamp " + std::to_string(p.stamp.ns) +
                           " ns is not positive");
  }
  const std::pair<const char*, const cv::Mat*> images[] = {{"left", &p.left}, {"right", &p.right}};
  for (const auto& [name, img] : images) {
    if (img->type() != CV_8UC1 || img->cols != p.width || img->rows != p.height) {
      return InvalidArgument(std::string(name) + " image is " + SizeText(img->cols, img->rows) +
                             " " + cv::typeToString(img->type()) + "; expected " +
                             SizeText(p.width, p.height) + " CV_8UC1");
    }
  }
  const std::pair<const char*, const CameraModelFields*> models[] = {{"left", &p.left_model},
                                                                     {"right", &p.right_model}};
  for (const auto& [name, m] : models) {
    if (m->width != p.width || m->height != p.height) {
      return InvalidArgument(std::string(name) + " camera model is for " +
                             SizeText(m->width, m->height) + " images but the frame is " +
                             SizeText(p.width, p.height));
    }
  }
  return Status::Ok();
}

}  // namespace rover::dl::stereo
