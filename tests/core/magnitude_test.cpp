// core/magnitude.h and core/memory.h: exact scaling by powers of two, over- and underflow named
// by scale_back, a scale-free norm, memory sizes parsed and printed.
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/core/magnitude.h"
#include "limsurf/core/memory.h"

namespace limsurf {
namespace {

TEST(Magnitude, ExponentBringsTheLargestEntryToOrderOne) {
    EXPECT_EQ(magnitude_exponent(Eigen::Vector3d(0.75, -3.0, 0.5)), 2);  // |x| max 3 in [2, 4)
    EXPECT_EQ(magnitude_exponent(Eigen::Vector3d(1.0, 0.0, 0.0)), 1);    // 1 in [1, 2)
    EXPECT_EQ(magnitude_exponent(Eigen::Vector3d::Zero()), 0);
    EXPECT_EQ(magnitude_exponent(Eigen::Vector2d(1.0, std::numeric_limits<double>::infinity())), 0);
    const Eigen::Vector3d huge(1.7e308, -1e308, 0.0);
    const Eigen::Vector3d scaled = times_power_of_two(huge, -magnitude_exponent(huge));
    EXPECT_LT(scaled.cwiseAbs().maxCoeff(), 1.0);
    EXPECT_GE(scaled.cwiseAbs().maxCoeff(), 0.5);
    // Exact both ways, subnormals included (two factors: 2^1070 does not fit one double).
    const Eigen::Vector2d tiny(4.9406564584124654e-324, 1e-310);
    const int e = magnitude_exponent(tiny);
    EXPECT_EQ(times_power_of_two(times_power_of_two(tiny, -e), e), tiny);
    EXPECT_EQ(times_power_of_two(times_power_of_two(huge, -1024), 1024), huge);
}

TEST(Magnitude, ScaleBackNamesOverflowAndUnderflow) {
    EXPECT_EQ(scale_back(0.75, 10, "area"), 768.0);
    EXPECT_EQ(scale_back(0.0, -5000, "volume"), 0.0);  // a true zero stays zero
    try {
        (void)scale_back(0.5, 3 * 1024, "enclosed volume");
        FAIL();
    } catch (const NumericalError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("the enclosed volume (about 1e924) overflows a double", 0), 0U)
            << e.what();
    }
    try {
        (void)scale_back(0.5, -1600, "inertia tensor");
        FAIL();
    } catch (const NumericalError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("the inertia tensor (about 1e-482) underflows a double", 0), 0U)
            << e.what();
    }
    // A subnormal result is an underflow too (precision lost), not a result.
    EXPECT_THROW((void)scale_back(0.5, -1030, "area"), NumericalError);
}

TEST(Magnitude, ScaleFreeNormIsTheNormWhereverItFits) {
    const Eigen::Matrix3d m = Eigen::Matrix3d::Random();
    EXPECT_NEAR(scale_free_norm(m), m.norm(), 1e-15 * m.norm());
    // Squares of 1e200 overflow; the norm does not.
    EXPECT_NEAR(scale_free_norm(Eigen::Vector2d(3e200, 4e200)) / 5e200, 1.0, 1e-15);
    EXPECT_NEAR(scale_free_norm(Eigen::Vector2d(3e-200, 4e-200)) / 5e-200, 1.0, 1e-15);
    // On a difference expression (where Eigen 3.4's stableNorm is wrong).
    const Eigen::Matrix3d a = Eigen::Matrix3d::Random();
    EXPECT_NEAR(scale_free_norm(a - m), (a - m).eval().norm(), 1e-15 * (a - m).eval().norm());
}

TEST(Memory, SizesParseAndPrint) {
    EXPECT_EQ(parse_memory_size("8G"), std::int64_t{8} << 30);
    EXPECT_EQ(parse_memory_size("512MiB"), std::int64_t{512} << 20);
    EXPECT_EQ(parse_memory_size("1.5k"), 1536);
    EXPECT_EQ(parse_memory_size("1000000"), 1000000);
    EXPECT_EQ(parse_memory_size("2tb"), std::int64_t{2} << 40);
    for (const char* bad : {"", "lots", "-1G", "0", "8X", "nan", "inf", "1e30G"}) {
        EXPECT_THROW((void)parse_memory_size(bad), InputError) << bad;
    }
    EXPECT_EQ(format_bytes(120), "120 bytes");
    EXPECT_EQ(format_bytes(std::int64_t{1} << 20), "1 MiB");
    EXPECT_EQ(format_bytes((std::int64_t{17} << 30) + (std::int64_t{7} << 29)), "20.5 GiB");
}

TEST(Memory, TheMachinesMemoryIsKnownHereAndTheBudgetIsThreeQuarters) {
    const std::int64_t machine = machine_memory_bytes();
    ASSERT_GT(machine, std::int64_t{1} << 26);  // Linux: sysconf answers
    EXPECT_EQ(default_memory_budget(), machine / 4 * 3);
}

}  // namespace
}  // namespace limsurf
