// `limsurf tune`: the paper's Table 1 rows through --lambda (cross-checked by `limsurf eigen`, whose
// spectrum comes from the scheme's own local subdivision matrix), the cup and saddle searches and
// their protection, the curve in JSON and CSV, and refusals (exit 1 naming the problem; usage
// errors 2).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "support/paths.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

using test::CliRun;

const fs::path& temp_dir() {
    static const fs::path dir = test::make_temp_dir("cli_tune");
    return dir;
}

CliRun limsurf(const std::vector<std::string>& args) {
    return test::run_limsurf(args, temp_dir());
}

nlohmann::json run_json(const std::vector<std::string>& args) {
    const CliRun run = limsurf(args);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return run.exit_code == 0 ? nlohmann::json::parse(run.out) : nlohmann::json::object();
}

double number(const nlohmann::json& j, const char* key) {
    return j.at(key).get<double>();
}

std::string weights_argument(const nlohmann::json& w) {
    std::ostringstream out;
    out.precision(17);
    out << number(w, "alpha") << ',' << number(w, "beta") << ',' << number(w, "gamma");
    return out.str();
}

// Table 1 of the paper (valence 5): the cup row at λ = 0.550, the saddle row at λ = 0.585, both
// from the relaxed system (31) (β = γ); the subdominant eigenvalue and λ₃ = λ² checked by the
// eigen command's numerical spectrum of the 2-ring subdivision matrix.
void check_table_one_row(const std::string& lambda_text, double alpha, double alpha_tolerance, double beta,
                         double beta_tolerance) {
    SCOPED_TRACE("lambda " + lambda_text);
    const nlohmann::json out = run_json({"tune", "--valence", "5", "--lambda", lambda_text, "--json"});
    ASSERT_TRUE(out.contains("candidates"));
    EXPECT_EQ(out.at("command").get<std::string>(), "tune");
    EXPECT_EQ(out.at("valence").get<int>(), 5);
    EXPECT_DOUBLE_EQ(number(out, "lambda"), std::stod(lambda_text));
    ASSERT_EQ(out.at("candidates").size(), 1u);
    const nlohmann::json& c = out.at("candidates")[0];
    EXPECT_EQ(c.at("constraint").get<std::string>(), "relaxed");
    EXPECT_NEAR(number(c, "alpha"), alpha, alpha_tolerance);
    EXPECT_NEAR(number(c, "beta"), beta, beta_tolerance);
    EXPECT_NEAR(number(c, "gamma"), beta, beta_tolerance);
    const double lambda = std::stod(lambda_text);
    EXPECT_NEAR(number(c, "lambda"), lambda, 1e-12);
    EXPECT_NEAR(number(c, "lambda3"), lambda * lambda, 1e-12);
    EXPECT_GT(number(c, "cup_error"), 0.0);
    EXPECT_GT(number(c, "saddle_error"), 0.0);
    // Table 1's "Original" row: α = 15, β = γ = 1, λ = 0.550 (three decimals).
    const nlohmann::json& cc = out.at("classical");
    EXPECT_EQ(cc.at("constraint").get<std::string>(), "none");
    EXPECT_DOUBLE_EQ(number(cc, "alpha"), 15.0);
    EXPECT_DOUBLE_EQ(number(cc, "beta"), 1.0);
    EXPECT_DOUBLE_EQ(number(cc, "gamma"), 1.0);
    EXPECT_NEAR(number(cc, "lambda"), 0.550, 5e-4);
    const nlohmann::json& f = out.at("feasible_range");
    EXPECT_LT(f[0].get<double>(), lambda);
    EXPECT_GT(f[1].get<double>(), lambda);

    const nlohmann::json spectrum =
        run_json({"eigen", "--scheme", "catmull-clark", "--valence", "5", "--weights", weights_argument(c), "--json"});
    ASSERT_TRUE(spectrum.contains("subdominant"));
    EXPECT_NEAR(number(spectrum, "subdominant"), lambda, 1e-9);
    // Frequency 0's largest after 1 is λ₃ = λ² (31c); frequency 2 holds λ₄ (free in (31), above λ²).
    const auto largest = [&](int frequency) {
        double value = 0.0;
        for (const nlohmann::json& e : spectrum.at("eigenvalues")) {
            const double abs = e.at("value").at("abs").get<double>();
            if (!e.at("frequency").is_null() && e.at("frequency").get<int>() == frequency && abs < 1.0 - 1e-9) {
                value = std::max(value, abs);
            }
        }
        return value;
    };
    EXPECT_NEAR(largest(1), lambda, 1e-9);
    EXPECT_NEAR(largest(0), lambda * lambda, 1e-9);
    EXPECT_NEAR(largest(2), number(c, "lambda4"), 1e-9);
    EXPECT_GT(number(c, "lambda4"), lambda * lambda);
}

TEST(CliTune, TableOneCupRow) {
    check_table_one_row("0.55", 13.4575, 5e-5, 0.999938, 5e-7);
}

TEST(CliTune, TableOneSaddleRow) {
    check_table_one_row("0.585", 13.9851, 5e-5, 0.824885, 1e-6);
}

TEST(CliTune, TableOneRowInText) {
    const CliRun run = limsurf({"tune", "--valence", "5", "--lambda", "0.55"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("candidate 1"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("13.4575"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("relaxed"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("catmull-clark"), std::string::npos) << run.out;
    EXPECT_FALSE(std::regex_search(run.out, std::regex(R"(\b(nan|inf)\b)"))) << run.out;
}

/// The searched shape's error and the other one's.
struct Errors {
    double shape = 0.0;
    double other = 0.0;
};

Errors errors_of(const nlohmann::json& w, bool cup) {
    const double c = number(w, "cup_error"), s = number(w, "saddle_error");
    return cup ? Errors{c, s} : Errors{s, c};
}

// The search: Fig. 7's reading (§3.3) that the optima 0.550 (cup) and 0.585 (saddle) are the ends
// of the interval where both errors are at most Catmull–Clark's.
void check_search(const nlohmann::json& out, const std::string& shape, double expected_lambda) {
    SCOPED_TRACE(shape);
    ASSERT_TRUE(out.contains("tuned"));
    const bool cup = shape == "cup";
    EXPECT_EQ(out.at("command").get<std::string>(), "tune");
    EXPECT_EQ(out.at("shape").get<std::string>(), shape);
    EXPECT_EQ(out.at("quadrature_points").get<int>(), 4);
    EXPECT_EQ(out.at("tile_levels").get<int>(), 10);
    EXPECT_DOUBLE_EQ(number(out, "poisson_ratio"), 0.3);
    EXPECT_TRUE(out.at("protect_other_shape").get<bool>());
    EXPECT_TRUE(out.at("protection_binds").get<bool>());
    const nlohmann::json& tuned = out.at("tuned");
    EXPECT_NEAR(number(tuned, "lambda"), expected_lambda, 5e-4);
    const Errors t = errors_of(tuned, cup);
    const Errors cc = errors_of(out.at("classical"), cup);
    EXPECT_LT(t.shape, cc.shape);
    EXPECT_LE(t.other, cc.other + 1e-12);
    // The unconstrained minimum is lower for the shape but raises the other error above Catmull–Clark's.
    const Errors u = errors_of(out.at("unconstrained"), cup);
    EXPECT_LE(u.shape, t.shape);
    EXPECT_GT(u.other, cc.other);
    const double unconstrained_lambda = number(out.at("unconstrained"), "lambda");
    if (cup) {
        EXPECT_LT(unconstrained_lambda, number(tuned, "lambda"));
    } else {
        EXPECT_GT(unconstrained_lambda, number(tuned, "lambda"));
    }
    // The curve: increasing λ over the whole search range (here the feasible range).
    const nlohmann::json& curve = out.at("curve");
    ASSERT_EQ(curve.size(), 21u);
    const nlohmann::json& range = out.at("search_range");
    EXPECT_EQ(range, out.at("feasible_range"));
    EXPECT_NEAR(number(curve.front(), "lambda"), range[0].get<double>(), 1e-9);
    EXPECT_NEAR(number(curve.back(), "lambda"), range[1].get<double>(), 1e-9);
    for (std::size_t i = 1; i < curve.size(); ++i) {
        EXPECT_LT(number(curve[i - 1], "lambda"), number(curve[i], "lambda")) << i;
    }
    // No sample of the curve beats the golden-section minimum by more than the search's resolution.
    for (const nlohmann::json& s : curve) {
        EXPECT_GE(errors_of(s, cup).shape, u.shape - 1e-9) << number(s, "lambda");
    }
}

TEST(CliTune, CupSearchAndCurveCsv) {
    const fs::path csv = temp_dir() / "cup_curve.csv";
    const nlohmann::json out =
        run_json({"tune", "--valence", "5", "--shape", "cup", "--samples", "21", "--curve", csv.string(), "--json"});
    check_search(out, "cup", 0.550);
    ASSERT_TRUE(fs::exists(csv));
    std::istringstream lines(test::slurp(csv));
    std::string line;
    ASSERT_TRUE(std::getline(lines, line));
    EXPECT_EQ(line, "lambda,alpha,beta,gamma,constraint,lambda3,lambda4,cup_error,saddle_error");
    std::size_t rows = 0;
    std::string first;
    while (std::getline(lines, line)) {
        if (!line.empty()) {
            first = rows == 0 ? line : first;
            ++rows;
        }
    }
    EXPECT_EQ(rows, out.at("curve").size());
    // The first row holds the curve's first λ.
    ASSERT_FALSE(first.empty());
    EXPECT_NEAR(std::stod(first.substr(0, first.find(','))), number(out.at("curve")[0], "lambda"), 1e-12);
}

TEST(CliTune, SaddleSearch) {
    check_search(run_json({"tune", "--valence", "5", "--shape", "saddle", "--samples", "21", "--json"}), "saddle",
                 0.585);
}

TEST(CliTune, UnprotectedSearchInARange) {
    const nlohmann::json out = run_json({"tune", "--valence", "5", "--shape", "cup", "--no-protect", "--lambda-range",
                                         "0.45,0.6", "--samples", "21", "--json"});
    ASSERT_TRUE(out.contains("tuned"));
    EXPECT_FALSE(out.at("protect_other_shape").get<bool>());
    EXPECT_FALSE(out.at("protection_binds").get<bool>());
    EXPECT_EQ(out.at("search_range"), nlohmann::json::array({0.45, 0.6}));
    EXPECT_EQ(out.at("tuned"), out.at("unconstrained"));
    EXPECT_NEAR(number(out.at("tuned"), "lambda"), 0.509, 0.01);  // §3.3: the cup's own minimum
    EXPECT_NEAR(number(out.at("curve").front(), "lambda"), 0.45, 1e-12);
    EXPECT_NEAR(number(out.at("curve").back(), "lambda"), 0.6, 1e-12);
}

// --threads shares the faces of each evaluation among threads: the same numbers as one thread
// (the search's time apart), and with --lambda too.
TEST(CliTune, ThreadsDoNotChangeTheResult) {
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"tune", "--valence", "7", "--samples", "5", "--json"},
          std::vector<std::string>{"tune", "--valence", "7", "--lambda", "0.6", "--json"},
          // The protection binds with several crossings, bisected at once on 2 and 3 threads.
          std::vector<std::string>{"tune", "--valence", "5", "--samples", "21", "--json"}}) {
        std::vector<nlohmann::json> outs;
        // The search's curve runs several λ at once, one per thread: 5 samples on 2 and 3 threads.
        for (const char* threads : {"1", "2", "3"}) {
            std::vector<std::string> with = args;
            with.insert(with.end(), {"--threads", threads});
            outs.push_back(run_json(with));
            outs.back().erase("time_seconds");
        }
        EXPECT_EQ(outs[0], outs[1]) << args[3];
        EXPECT_EQ(outs[0], outs[2]) << args[3];
        if (args[4] == "21") {
            ASSERT_TRUE(outs[0].at("protection_binds").get<bool>());
            const double limit = outs[0].at("classical").at("saddle_error").get<double>();
            const auto& curve = outs[0].at("curve");
            int crossings = 0;
            for (std::size_t i = 0; i + 1 < curve.size(); ++i) {
                crossings += (curve[i].at("saddle_error").get<double>() <= limit) !=
                             (curve[i + 1].at("saddle_error").get<double>() <= limit);
            }
            EXPECT_GE(crossings, 2) << "the case no longer bisects several crossings at once";
        }
    }
}

TEST(CliTune, SearchInText) {
    const CliRun run = limsurf({"tune", "--valence", "5", "--shape", "saddle", "--samples", "11"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    for (const char* word : {"tuned", "unconstrained", "catmull-clark", "protection binds", "feasible lambda"}) {
        EXPECT_NE(run.out.find(word), std::string::npos) << word << "\n" << run.out;
    }
    EXPECT_FALSE(std::regex_search(run.out, std::regex(R"(\b(nan|inf)\b)"))) << run.out;
}

void expect_refused(const std::vector<std::string>& args, int code, const std::string& message) {
    std::string line = "limsurf";
    for (const std::string& a : args) {
        line += " " + a;
    }
    SCOPED_TRACE(line);
    const CliRun run = limsurf(args);
    EXPECT_EQ(run.exit_code, code) << run.out;
    EXPECT_NE(run.err.find(message), std::string::npos) << run.err;
}

TEST(CliTune, RefusalsNameTheProblem) {
    expect_refused({"tune", "--valence", "4"}, 1, "valence 4 is the regular");
    expect_refused({"tune", "--valence", "4", "--lambda", "0.5"}, 1, "valence 4 is the regular");
    expect_refused({"tune", "--valence", "2"}, 1, "valence 2 is outside");
    expect_refused({"tune", "--valence", "100000"}, 1, "valence 100000 is outside");
    expect_refused({"tune", "--valence", "5", "--lambda", "0.9"}, 1, "outside the feasible range");
    expect_refused({"tune", "--valence", "5", "--lambda", "nan"}, 1, "outside the feasible range");
    expect_refused({"tune", "--valence", "5", "--lambda-range", "0.6,0.5"}, 1, "--lambda-range");
    expect_refused({"tune", "--valence", "5", "--lambda-range", "0.5"}, 1, "--lambda-range");
    expect_refused({"tune", "--valence", "5", "--lambda-range", "0.5,0.6,0.7"}, 1, "--lambda-range");
    expect_refused({"tune", "--valence", "5", "--lambda-range", "0.1,0.6"}, 1, "not inside the feasible range");
    expect_refused({"tune", "--valence", "5", "--samples", "2"}, 1, "samples");
    expect_refused({"tune", "--valence", "5", "--quadrature", "0"}, 1, "quadrature points");
    expect_refused({"tune", "--valence", "5", "--lambda", "0.55", "--quadrature", "11"}, 1, "quadrature points");
    expect_refused({"tune", "--valence", "5", "--tile-levels", "21"}, 1, "tile levels");
    expect_refused({"tune", "--valence", "5", "--poisson-ratio", "0.7"}, 1, "Poisson's ratio");
    // Usage errors: an unknown shape, options of the search with --lambda, no valence.
    expect_refused({"tune", "--valence", "5", "--shape", "bowl"}, 2, "--shape");
    expect_refused({"tune", "--valence", "5", "--lambda", "0.55", "--shape", "cup"}, 2, "excludes");
    expect_refused({"tune", "--shape", "cup"}, 2, "--valence");
    // A refused run leaves no curve behind.
    const fs::path csv = temp_dir() / "refused.csv";
    expect_refused({"tune", "--valence", "5", "--samples", "2", "--curve", csv.string()}, 1, "samples");
    EXPECT_FALSE(fs::exists(csv));
}

}  // namespace
}  // namespace limsurf
