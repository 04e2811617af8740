#pragma once
// Private to dl_stereo: pieces of the filters that the pipeline runs in parallel.

#include "rover/dl/stereo/disparity_image.hpp"

namespace rover::dl::stereo::internal {

// The overhang filter (filters.hpp) on columns [u_begin, u_end) only; columns are independent,
// so disjoint ranges may run on different threads. Parameters are not checked.
void OverhangColumns(double tolerance_px, double ratio, int search_rows, int u_begin, int u_end,
                     DisparityImage* disparity);

}  // namespace rover::dl::stereo::internal
