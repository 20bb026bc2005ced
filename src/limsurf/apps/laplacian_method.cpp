#include "limsurf/apps/laplacian_method.h"

#include <array>
#include <utility>

#include "limsurf/core/error.h"

namespace limsurf {
namespace {

constexpr std::array<std::pair<LaplacianMethod, const char*>, 5> method_names{{{LaplacianMethod::Dec, "dec"},
                                                                               {LaplacianMethod::DecSnap, "decsnap"},
                                                                               {LaplacianMethod::Sec, "sec"},
                                                                               {LaplacianMethod::SecSnap, "secsnap"},
                                                                               {LaplacianMethod::Iga, "iga"}}};

}  // namespace

const char* to_string(LaplacianMethod method) noexcept {
    for (const auto& [value, name] : method_names) {
        if (value == method) {
            return name;
        }
    }
    return "?";
}

LaplacianMethod parse_laplacian_method(const std::string& name) {
    for (const auto& [value, method_name] : method_names) {
        if (name == method_name) {
            return value;
        }
    }
    throw InputError("unknown method '" + name + "' (expected dec, decsnap, sec, secsnap or iga)");
}

InnerProductMethod inner_product_method(LaplacianMethod method) {
    LIMSURF_CHECK(method != LaplacianMethod::Iga, InputError,
                  "iga has no inner products of forms (it integrates on the limit surface)");
    return parse_inner_product_method(to_string(method));
}

}  // namespace limsurf
