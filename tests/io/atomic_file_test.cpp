#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/atomic_file.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/io/vertex_field.h"
#include "support/paths.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::size_t entries(const fs::path& dir) {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) {
        ++n;
    }
    return n;
}

TEST(AtomicFile, WritesTheFileAndNothingElse) {
    const fs::path dir = test::make_temp_dir("atomic");
    const fs::path path = dir / "out.txt";
    write_file_atomically(path, [](std::ostream& out) { out << "hello\n"; });
    EXPECT_EQ(slurp(path), "hello\n");
    EXPECT_EQ(entries(dir), 1U);
    fs::remove_all(dir);
}

TEST(AtomicFile, AWriterThatThrowsLeavesNoTargetAndNoTemporaryFile) {
    const fs::path dir = test::make_temp_dir("atomic");
    const fs::path path = dir / "out.txt";
    EXPECT_THROW(write_file_atomically(path,
                                       [](std::ostream& out) {
                                           out << std::string(100000, 'x');
                                           throw std::runtime_error("midway");
                                       }),
                 std::runtime_error);
    EXPECT_FALSE(fs::exists(path));
    EXPECT_EQ(entries(dir), 0U);
    fs::remove_all(dir);
}

TEST(AtomicFile, ReplacesAnExistingFileWholeOrNotAtAll) {
    const fs::path dir = test::make_temp_dir("atomic");
    const fs::path path = dir / "out.txt";
    {
        std::ofstream old(path);
        old << std::string(5000, 'o');
    }
    fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write);
    write_file_atomically(path, [](std::ostream& out) { out << "new"; });
    EXPECT_EQ(slurp(path), "new");
    EXPECT_EQ(fs::status(path).permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);

    EXPECT_THROW(write_file_atomically(path,
                                       [](std::ostream& out) {
                                           out << "partial";
                                           throw InputError("stop");
                                       }),
                 InputError);
    EXPECT_EQ(slurp(path), "new");
    EXPECT_EQ(entries(dir), 1U);
    fs::remove_all(dir);
}

TEST(AtomicFile, UnwritableLocationsNameThePath) {
    const fs::path dir = test::make_temp_dir("atomic");
    const fs::path missing = dir / "no" / "such" / "dir" / "out.txt";
    try {
        write_file_atomically(missing, [](std::ostream& out) { out << "x"; });
        FAIL() << "no error";
    } catch (const InputError& error) {
        EXPECT_EQ(std::string(error.what()).rfind(missing.string() + ": cannot create", 0), 0U) << error.what();
    }
    try {
        write_file_atomically(dir, [](std::ostream& out) { out << "x"; });
        FAIL() << "no error";
    } catch (const InputError& error) {
        EXPECT_EQ(std::string(error.what()), dir.string() + ": cannot write: is a directory");
    }
    EXPECT_EQ(entries(dir), 0U);
    fs::remove_all(dir);
}

TEST(AtomicFile, AStreamFailureIsAnError) {
    const fs::path dir = test::make_temp_dir("atomic");
    const fs::path path = dir / "out.txt";
    EXPECT_THROW(write_file_atomically(path,
                                       [](std::ostream& out) {
                                           out << "x";
                                           out.setstate(std::ios::badbit);
                                       }),
                 InputError);
    EXPECT_EQ(entries(dir), 0U);
    fs::remove_all(dir);
}

TEST(AtomicFile, WriteMeshWithAMalformedSoupCreatesNothing) {
    const fs::path dir = test::make_temp_dir("atomic");
    PolygonSoup soup;
    soup.positions.setZero(2, 3);
    soup.add_face(std::vector<Index>{0, 1, 5});
    for (const char* name : {"m.obj", "m.off", "m.ply"}) {
        EXPECT_THROW((void)write_mesh(dir / name, soup), InputError) << name;
    }
    EXPECT_EQ(entries(dir), 0U);
    fs::remove_all(dir);
}

TEST(AtomicFile, ASymbolicLinkKeepsPointingAtItsReplacedTarget) {
    const fs::path dir = test::make_temp_dir("atomic");
    std::ofstream(dir / "target.txt") << "old\n";
    fs::create_symlink("target.txt", dir / "link.txt");
    write_file_atomically(dir / "link.txt", [](std::ostream& out) { out << "new\n"; });
    EXPECT_TRUE(fs::is_symlink(dir / "link.txt"));
    EXPECT_EQ(slurp(dir / "target.txt"), "new\n");
    // A dangling link: the target is created; a loop of links is refused.
    fs::create_symlink("made.txt", dir / "dangling.txt");
    write_file_atomically(dir / "dangling.txt", [](std::ostream& out) { out << "made\n"; });
    EXPECT_EQ(slurp(dir / "made.txt"), "made\n");
    fs::create_symlink("loop.txt", dir / "loop.txt");
    EXPECT_THROW(write_file_atomically(dir / "loop.txt", [](std::ostream& out) { out << "x"; }), InputError);
    EXPECT_EQ(entries(dir), 5U);  // target, link, dangling, made, loop: no temporary file left
    fs::remove_all(dir);
}

TEST(AtomicFile, DevicesAreWrittenThroughAndStayDevices) {
    write_file_atomically("/dev/null", [](std::ostream& out) { out << "discarded\n"; });
    EXPECT_TRUE(fs::is_character_file("/dev/null"));
    if (fs::exists("/dev/full")) {
        try {
            write_file_atomically("/dev/full", [](std::ostream& out) { out << std::string(1 << 16, 'x'); });
            FAIL() << "writing /dev/full succeeded";
        } catch (const InputError& error) {
            EXPECT_EQ(std::string(error.what()).rfind("/dev/full: write failed", 0), 0U) << error.what();
        }
        EXPECT_TRUE(fs::is_character_file("/dev/full"));
    }
}

TEST(VertexValues, OneFiniteNumberPerLineAndOnePerVertex) {
    const fs::path dir = test::make_temp_dir("values");
    std::ofstream(dir / "ok.txt") << "\xEF\xBB\xBF# values\n1.5\n\n-2 # second\r3e-3\n";
    const Eigen::VectorXd values = read_vertex_values(dir / "ok.txt", 3);
    EXPECT_EQ(values, Eigen::Vector3d(1.5, -2, 3e-3));
    const auto message = [&](const char* text, Index count) {
        std::ofstream(dir / "bad.txt") << text;
        try {
            (void)read_vertex_values(dir / "bad.txt", count);
        } catch (const InputError& error) {
            return std::string(error.what());
        }
        return std::string("no error");
    };
    const std::string bad = (dir / "bad.txt").string();
    EXPECT_EQ(message("1\n2 3\n", 2), bad + ":2: expected one number, got 2 fields");
    EXPECT_EQ(message("1\nnan\n", 2), bad + ":2: value 'nan' is not finite");
    EXPECT_EQ(message("1\n2\n3\n", 2), bad + ":3: more than 2 values (one per vertex)");
    EXPECT_EQ(message("1\n", 2), bad + ": 1 values, but the mesh has 2 vertices");
    try {
        (void)read_vertex_values(dir, 1);
        FAIL();
    } catch (const InputError& error) {
        EXPECT_EQ(std::string(error.what()), dir.string() + ": cannot open: is a directory");
    }
    fs::remove_all(dir);
}

TEST(VertexValues, WrittenValuesReadBackBitForBitAndNonFiniteWritesNothing) {
    const fs::path dir = test::make_temp_dir("values_out");
    const Eigen::Vector4d values(0.1, -1.0 / 3.0, 6.02214076e23, -4.9e-324);
    write_values(dir / "w.txt", values);
    EXPECT_EQ(read_vertex_values(dir / "w.txt", 4), values);  // 17 digits: exact round trip
    const Eigen::Vector2d bad(1.0, std::numeric_limits<double>::infinity());
    try {
        write_values(dir / "bad.txt", bad);
        FAIL();
    } catch (const InputError& error) {
        EXPECT_EQ(std::string(error.what()),
                  (dir / "bad.txt").string() + ": value 1 is inf (not finite): nothing written");
    }
    EXPECT_FALSE(fs::exists(dir / "bad.txt"));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace limsurf
