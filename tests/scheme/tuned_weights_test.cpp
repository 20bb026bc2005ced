#include <fstream>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/scheme/tuned_weights.h"
#include "support/paths.h"

namespace limsurf {
namespace {

TEST(TunedWeights, CatmullClarkWeightsAreTheBSplineAtValenceFour) {
    const VertexRuleWeights w = catmull_clark_weights(4);
    EXPECT_EQ(w.alpha, 8.0);  // iga-tuned-catmull-clark-weights §2: α = 8, β = γ = 1 for v = 4
    EXPECT_EQ(w.beta, 1.0);
    EXPECT_EQ(w.gamma, 1.0);
    EXPECT_EQ(catmull_clark_weights(5).alpha, 15.0);  // Table 1, "Original"
}

TEST(TunedWeights, PresetsAreTheTableOneValues) {
    const TunedWeights cup = TunedWeights::preset("cup");
    EXPECT_EQ(cup.at(0, 5).alpha, 13.4575);
    EXPECT_EQ(cup.at(0, 5).beta, 0.999938);
    EXPECT_EQ(cup.at(0, 5).gamma, 0.999938);
    EXPECT_EQ(cup.at(0, 6).alpha, 24.0);  // other valences stay Catmull–Clark
    const TunedWeights saddle = TunedWeights::preset("saddle");
    EXPECT_EQ(saddle.at(3, 5).alpha, 13.9851);
    EXPECT_EQ(saddle.at(3, 5).beta, 0.824885);
    EXPECT_TRUE(TunedWeights::preset("catmull-clark").is_catmull_clark());
    EXPECT_THROW((void)TunedWeights::preset("bowl"), InputError);
}

TEST(TunedWeights, VertexOverridesWinOverValences) {
    TunedWeights weights = TunedWeights::preset("cup");
    weights.set_vertex(7, {13.9851, 0.824885, 0.824885});
    EXPECT_EQ(weights.at(7, 5).alpha, 13.9851);
    EXPECT_EQ(weights.at(8, 5).alpha, 13.4575);
    EXPECT_THROW(weights.set_valence(2, {1, 1, 1}), InputError);
    EXPECT_THROW(weights.set_vertex(0, {0, 1, 1}), InputError);
    EXPECT_THROW(weights.set_vertex(0, {1, -1, 1}), InputError);
}

TEST(TunedWeights, ReadFromAFile) {
    const auto dir = test::make_temp_dir("weights");
    {
        std::ofstream out(dir / "w.txt");
        out << "# valence alpha beta gamma\n5 13.4575 0.999938 0.999938\nvertex 12 13.9851 0.824885 0.824885\n";
    }
    const TunedWeights weights = TunedWeights::from_file(dir / "w.txt");
    EXPECT_EQ(weights.at(0, 5).alpha, 13.4575);
    EXPECT_EQ(weights.at(12, 5).alpha, 13.9851);
    {
        std::ofstream out(dir / "bad.txt");
        out << "5 13.4575 0.999938\n";
    }
    try {
        (void)TunedWeights::from_file(dir / "bad.txt");
        FAIL() << "expected an error";
    } catch (const InputError& error) {
        EXPECT_EQ(std::string(error.what()), (dir / "bad.txt").string() + ":1: expected 'valence alpha beta gamma'");
    }
}

}  // namespace
}  // namespace limsurf
