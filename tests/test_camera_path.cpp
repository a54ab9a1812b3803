// Camera path CSV: round trip, interpolation, and clear errors on bad files.
#include "assets.hpp"

#include "tinlod/camera_path.hpp"
#include "tinlod/error.hpp"

#include <gtest/gtest.h>

using namespace tinlod;

TEST(CameraPath, RoundTripKeepsEveryKeyframeExactly) {
    CameraPath path;
    path.keys = {{0.0, {1.0 / 3, 2.5, 1e6 + 0.1}, {4, 5, 6}}, {0.75, {7, 8, 9}, {-1, -2, -3.125}}};
    const std::string file = tinlod::test::temp_dir() + "/path.csv";
    write_camera_path(path, file);
    const CameraPath back = read_camera_path(file);
    ASSERT_EQ(back.keys.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(back.keys[i].t, path.keys[i].t);
        EXPECT_EQ(back.keys[i].eye, path.keys[i].eye);
        EXPECT_EQ(back.keys[i].at, path.keys[i].at);
    }
}

TEST(CameraPath, InterpolatesLinearlyAndClamps) {
    const CameraPath path = parse_camera_path(
        "t,eye_x,eye_y,eye_z,at_x,at_y,at_z\n0,0,0,10,1,0,0\n2,20,0,30,21,0,0\n", "p");
    const View base;
    EXPECT_EQ(path.at_time(1.0, base).eye, glm::dvec3(10, 0, 20));
    EXPECT_EQ(path.at_time(-5.0, base).eye, glm::dvec3(0, 0, 10));
    EXPECT_EQ(path.at_time(9.0, base).at, glm::dvec3(21, 0, 0));
    const auto views = path.sample(5, base);
    ASSERT_EQ(views.size(), 5u);
    EXPECT_EQ(views[2].eye, glm::dvec3(10, 0, 20));
    EXPECT_EQ(views.back().eye, glm::dvec3(20, 0, 30));
}

TEST(CameraPath, BadFilesNameTheLineAndProblem) {
    const std::pair<const char *, const char *> cases[] = {
        {"", "empty camera path"},
        {"x,y,z\n", "line 1: expected the header"},
        {"t,eye_x,eye_y,eye_z,at_x,at_y,at_z\n", "no keyframe"},
        {"t,eye_x,eye_y,eye_z,at_x,at_y,at_z\n0,1,2,3,4,5\n", "line 2: expected 7"},
        {"t,eye_x,eye_y,eye_z,at_x,at_y,at_z\n0,1,2,nan,4,5,6\n", "'nan' is not a finite number"},
        {"t,eye_x,eye_y,eye_z,at_x,at_y,at_z\n0,1,2,3,4,5,6\n0,1,2,3,4,5,6\n",
         "line 3: t must increase"},
        {"t,eye_x,eye_y,eye_z,at_x,at_y,at_z\n0,1,2,3,1,2,3\n", "coincide"},
        {"t,eye_x,eye_y,eye_z,at_x,at_y,at_z\n0,1,2,3,4,5,6x\n", "'6x' is not a finite number"},
    };
    for (const auto &[text, message] : cases) {
        SCOPED_TRACE(text);
        try {
            parse_camera_path(text, "path.csv");
            ADD_FAILURE() << "no error";
        } catch (const Error &e) {
            EXPECT_EQ(e.subject(), "path.csv");
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
        }
    }
}
