#pragma once
// Helpers of the recording tests: serialised samples of the stack's types, written by hand in
// XCDR1 (the header every type starts with, then padding bytes as the payload), and temporary
// folders.

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdint>
#include <string>
#include <vector>

#include "rover/recording/cdr.hpp"

namespace rover::recording::testing {

inline std::string MakeTempDir(const std::string& prefix) {
  std::string templ = ::testing::TempDir() + "/" + prefix + "-XXXXXX";
  EXPECT_NE(mkdtemp(templ.data()), nullptr);
  return templ;
}

/// A sample that starts with rover::Header{stamp_ns, frame_id, seq} and has `extra` more bytes.
inline std::vector<std::uint8_t> HeaderSample(std::int64_t stamp_ns, std::uint32_t seq,
                                              std::size_t extra = 0,
                                              const std::string& frame = "rover") {
  CdrWriter w;
  w.Int64(stamp_ns);
  w.String(frame);
  w.Uint32(seq);
  for (std::size_t i = 0; i < extra; ++i) w.Bool(i % 2 == 0);
  return std::move(w).Finish();
}

}  // namespace rover::recording::testing
