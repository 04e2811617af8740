// The shipped vision service set (deploy/vision.compose.yaml) end to end: roverctl starts the
// simulator, the drivers, dl-pose, dl-stereo and dl-vo on a fresh DDS domain; an operator's
// dl/range_request makes dl-stereo ask ddl-camera for a pair, the simulator renders it, and the
// range image that comes back must describe the ground the rover stands on. Then a
// dl/mast_command points the mast through dl-mast and ddl-motor, and a NAVCAM pair taken
// afterwards must carry the NAVCAM models moved by the measured mast angles (FIDO's "camera
// models transferred by mast joint angles").
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "rover/base/process.hpp"
#include "rover/hwconfig/rover_description.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/testing/test_support.hpp"

namespace rover {
namespace {

TEST(VisionSetE2e, RangeRequestOnSimulatorImagesGivesTheGround) {
  testing::UseLoopbackDds();  // for roverctl and for this process, whatever the shell exported
  const std::string dir = testing::MakeTempDir("vision-e2e");
  SpawnOptions o;
  o.argv = {testing::BinDir() + "/roverctl", "up",
            testing::SourceDir() + "/deploy/vision.compose.yaml"};
  o.env["ROVER_STATE_DIR"] = dir + "/state";
  o.stdout_path = dir + "/roverctl.log";
  o.stderr_path = dir + "/roverctl.log";
  auto roverctl = Process::Spawn(o);
  ASSERT_TRUE(roverctl.ok()) << roverctl.status().message();

  // Up: every service started and healthy (dl-pose levels for 10 s of simulated time first).
  nlohmann::json state;
  const bool up = testing::WaitFor(
      [&] {
        std::ifstream in(dir + "/state/vision/state.json");
        if (!in) return false;
        try {
          state = nlohmann::json::parse(in);
        } catch (...) {
          return false;
        }
        return state.value("phase", "") == "up";
      },
      std::chrono::seconds(120));
  ASSERT_TRUE(up) << testing::ReadFile(dir + "/roverctl.log");
  const int domain = state.value("domain", -1);
  ASSERT_GE(domain, 0);

  // The test's own participant joins the set's domain with the set's (loopback) configuration.
  auto participant = testing::JoinDomain(domain);
  ASSERT_TRUE(participant.ok()) << participant.status().message();
  auto req_w = dds::Writer<rover_dl_RangeRequest>::Create(*participant, "dl/range_request");
  auto range_r = dds::Reader<rover_dl_RangeImage>::Create(*participant, "dl/range_image");
  ASSERT_TRUE(req_w.ok() && range_r.ok());
  ASSERT_TRUE(testing::WaitFor([&] { return req_w->MatchedReaders() >= 1; }));

  rover_dl_RangeRequest req{};
  req.request_id = 7;
  req.camera = rover_CAMERA_FRONT_HAZCAM;
  req.width = 256;
  std::vector<float> xyz;
  std::vector<std::uint8_t> valid;
  int width = 0, height = 0;
  // Repeat the request until the set answers (one sent while dl-stereo was still matching may
  // be lost; it serves requests in order).
  auto last = std::chrono::steady_clock::now() - std::chrono::seconds(60);
  const bool got = testing::WaitFor(
      [&] {
        if (std::chrono::steady_clock::now() - last > std::chrono::seconds(20)) {
          EXPECT_TRUE(req_w->Write(req).ok());
          last = std::chrono::steady_clock::now();
        }
        for (auto& s : range_r->Take()) {
          if (s->request_id != 7) continue;
          width = s->width;
          height = s->height;
          xyz.assign(s->xyz._buffer, s->xyz._buffer + s->xyz._length);
          valid.assign(s->valid._buffer, s->valid._buffer + s->valid._length);
        }
        return !valid.empty();
      },
      std::chrono::seconds(90));

  // Mast: point by angles, wait for AT_GOAL, then take a NAVCAM pair.
  auto mast_w = dds::Writer<rover_dl_MastCommand>::Create(*participant, "dl/mast_command");
  auto mast_r = dds::Reader<rover_dl_MastStatus>::Create(*participant, "dl/mast_status");
  auto cam_w = dds::Writer<rover_ddl_StereoRequest>::Create(*participant, "ddl/camera_request");
  auto frame_r = dds::Reader<rover_ddl_StereoFrame>::Create(*participant, "ddl/stereo_frame");
  ASSERT_TRUE(mast_w.ok() && mast_r.ok() && cam_w.ok() && frame_r.ok());
  EXPECT_TRUE(testing::WaitFor([&] { return mast_w->MatchedReaders() >= 1; }));
  EXPECT_TRUE(testing::WaitFor([&] { return cam_w->MatchedReaders() >= 1; }));
  rover_dl_MastCommand mc{};
  mc.command_id = 31;
  mc.pointing = rover_dl_MAST_POINT_ANGLES;
  mc.pan = 0.5;
  mc.tilt = -0.4;
  EXPECT_TRUE(mast_w->Write(mc).ok());
  rover_dl_MastStatus mast{};
  const bool pointed = testing::WaitFor(
      [&] {
        for (auto& s : mast_r->Take()) {
          if (s->command_id == 31) mast = s.data();
        }
        return mast.command_id == 31 && mast.state != rover_dl_MAST_MOVING;
      },
      std::chrono::seconds(60));
  rover_ddl_StereoFrame navcam{};
  bool got_navcam = false;
  if (pointed && mast.state == rover_dl_MAST_AT_GOAL) {
    rover_ddl_StereoRequest cr{};
    cr.request_id = 901;
    cr.camera = rover_CAMERA_NAVCAM;
    cr.width = 256;
    EXPECT_TRUE(cam_w->Write(cr).ok());
    got_navcam = testing::WaitFor(
        [&] {
          for (auto& f : frame_r->Take()) {
            if (f->request_id != 901) continue;
            navcam.camera = f->camera;
            navcam.health = f->health;
            navcam.left_model = f->left_model;
            navcam.right_model = f->right_model;
            got_navcam = true;
          }
          return got_navcam;
        },
        std::chrono::seconds(90));
  }
  kill(static_cast<pid_t>(roverctl->pid()), SIGINT);
  const auto exit = roverctl->WaitFor(std::chrono::seconds(30));
  EXPECT_TRUE(exit.has_value());
  ASSERT_TRUE(got) << "no dl/range_image; roverctl log:\n" << testing::ReadFile(dir + "/roverctl.log");

  ASSERT_EQ(static_cast<int>(valid.size()), width * height);
  ASSERT_EQ(xyz.size(), 3 * valid.size());
  // The ground in front of the rover: most pixels ranged, points ahead of the rover and near
  // the rover's ground plane (the default terrain has gentle hills and small rocks).
  std::vector<double> z;
  int ahead = 0;
  for (std::size_t i = 0; i < valid.size(); ++i) {
    if (!valid[i]) continue;
    z.push_back(xyz[3 * i + 2]);
    if (xyz[3 * i] > 0.3) ++ahead;
  }
  const double density = static_cast<double>(z.size()) / static_cast<double>(valid.size());
  ASSERT_FALSE(z.empty());
  std::nth_element(z.begin(), z.begin() + static_cast<long>(z.size() / 2), z.end());
  const double median_z = z[z.size() / 2];
  std::printf("[ info ] %dx%d range image: %.1f %% valid, median z %.3f m\n", width, height,
              100.0 * density, median_z);
  EXPECT_GT(density, 0.3);
  EXPECT_GT(ahead, static_cast<int>(0.9 * static_cast<double>(z.size())));
  EXPECT_LT(std::abs(median_z), 0.25);

  // The mast reached the goal, and the NAVCAM models are the head-frame calibration (the rover
  // description's NAVCAM mount, which deploy/config/cameras.yaml matches) moved by the measured
  // mast angles: C = rover_from_head * C_head, A = R_head * A_head.
  ASSERT_TRUE(pointed) << "no terminal dl/mast_status; roverctl log:\n"
                       << testing::ReadFile(dir + "/roverctl.log");
  ASSERT_EQ(mast.state, rover_dl_MAST_AT_GOAL) << mast.message;
  EXPECT_NEAR(mast.pan, 0.5, 0.01);
  EXPECT_NEAR(mast.tilt, -0.4, 0.01);
  ASSERT_TRUE(got_navcam) << "no NAVCAM frame";
  EXPECT_EQ(navcam.camera, rover_CAMERA_NAVCAM);
  EXPECT_EQ(navcam.health, rover_HEALTH_OK);
  const hwconfig::RoverDescription rover;
  const Eigen::Isometry3d rover_from_head = rover.mast.HeadPose(mast.pan, mast.tilt);
  const auto vec = [](const double (&v)[3]) { return Eigen::Vector3d(v[0], v[1], v[2]); };
  const Eigen::Vector3d boresight = rover_from_head.linear() * rover.navcam.Pose().linear().col(0);
  for (int side = 0; side < 2; ++side) {
    const rover_ddl_CameraModel& m = side == 0 ? navcam.left_model : navcam.right_model;
    const Eigen::Vector3d c_expected = rover_from_head * rover.navcam.CameraCentre(side);
    EXPECT_LT((vec(m.c) - c_expected).norm(), 1e-3) << "side " << side;
    EXPECT_LT((vec(m.a) - boresight).norm(), 1e-3) << "side " << side;
  }
  std::printf("[ info ] mast at pan %.4f, tilt %.4f rad; NAVCAM left A (%.4f, %.4f, %.4f)\n",
              mast.pan, mast.tilt, navcam.left_model.a[0], navcam.left_model.a[1],
              navcam.left_model.a[2]);
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
}

}  // namespace
}  // namespace rover
