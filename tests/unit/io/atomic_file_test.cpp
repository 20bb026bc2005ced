#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/atomic_file.h"
#include "limsurf/io/mesh_io.h"
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

}  // namespace
}  // namespace limsurf
