#include "limsurf/io/face_groups.h"

#include <algorithm>
#include <charconv>
#include <cstddef>
#include <string_view>
#include <vector>

#include "limsurf/core/error.h"
#include "limsurf/core/input_file.h"
#include "limsurf/detail/io_text.h"

namespace limsurf {
namespace {

using detail::io_fail;
using detail::io_quote;

/// Integer groups name every number up to the largest: keep that list small.
constexpr long long max_group_number = 65535;

/// One entry of the file: its token and line.
struct Entry {
    std::string token;
    long long line = 0;
};

/// The whole of @p token as a decimal integer (optional leading '-'), if it is one.
bool as_integer(std::string_view token, long long& value) {
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, value);
    return ec == std::errc() && ptr == end;
}

std::vector<Entry> read_entries(std::istream& in, const std::string& file, Index num_faces) {
    detail::IoLineReader reader(in, file);
    std::vector<Entry> entries;
    std::vector<std::string_view> tokens;
    std::string line;
    bool saw_line = false;
    while (reader.next(line)) {
        saw_line = true;
        detail::io_split(detail::io_strip_comment(line), tokens);
        if (tokens.empty()) {
            continue;
        }
        if (tokens.size() != 1) {
            io_fail(file, reader.line_number(),
                    "expected one group (a name or an integer) per line, found " + std::to_string(tokens.size()) +
                        " tokens");
        }
        if (entries.size() == static_cast<std::size_t>(num_faces)) {
            io_fail(file, reader.line_number(),
                    "entry " + std::to_string(entries.size() + 1) + " " + io_quote(tokens[0]) + ", but the mesh has " +
                        std::to_string(num_faces) + " faces");
        }
        entries.push_back(Entry{std::string(tokens[0]), reader.line_number()});
    }
    if (!saw_line && num_faces > 0) {
        io_fail(file, 0, "empty file");
    }
    if (entries.size() != static_cast<std::size_t>(num_faces)) {
        io_fail(file, 0,
                std::to_string(entries.size()) + " entries, the mesh has " + std::to_string(num_faces) + " faces");
    }
    return entries;
}

/// All-integer files: the integers are the group numbers, named "0" … "max".
bool integer_groups(const std::vector<Entry>& entries, const std::string& file, FaceGroups& groups) {
    std::vector<long long> values(entries.size());
    long long largest = -1;
    for (std::size_t i = 0; i < entries.size(); ++i) {
        if (!as_integer(entries[i].token, values[i])) {
            return false;
        }
        largest = std::max(largest, values[i]);
    }
    for (std::size_t i = 0; i < entries.size(); ++i) {
        if (values[i] < -1 || values[i] > max_group_number) {
            io_fail(file, entries[i].line,
                    "group " + io_quote(entries[i].token) + " out of range (-1 for no group, else 0 to " +
                        std::to_string(max_group_number) + ")");
        }
    }
    for (long long g = 0; g <= largest; ++g) {
        groups.names.push_back(std::to_string(g));
    }
    for (const long long value : values) {
        groups.face_group.push_back(static_cast<Index>(value));
    }
    return true;
}

}  // namespace

FaceGroups read_face_groups(std::istream& in, const std::string& source_name, Index num_faces) {
    LIMSURF_CHECK(num_faces >= 0, InputError, source_name, ": the mesh has ", num_faces, " faces");
    const std::vector<Entry> entries = read_entries(in, source_name, num_faces);
    FaceGroups groups;
    if (integer_groups(entries, source_name, groups)) {
        if (groups.names.empty()) {
            groups.face_group.clear();  // every face in no group: no groups
        }
        return groups;
    }
    for (const Entry& entry : entries) {
        groups.face_group.push_back(groups.add_name(entry.token));
    }
    return groups;
}

FaceGroups read_face_groups(const std::filesystem::path& path, Index num_faces) {
    std::ifstream in = open_input_file(path);
    return read_face_groups(in, path.string(), num_faces);
}

}  // namespace limsurf
