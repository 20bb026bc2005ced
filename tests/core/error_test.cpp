#include <gtest/gtest.h>

#include "limsurf/core/error.h"

namespace limsurf {
namespace {

void needs_positive(int x) {
    LIMSURF_CHECK(x > 0, InputError, "x must be positive, got ", x);
}

TEST(Error, CheckThrowsTheNamedTypeWithTheMessage) {
    EXPECT_NO_THROW(needs_positive(1));
    try {
        needs_positive(-3);
        FAIL() << "expected an InputError";
    } catch (const InputError& error) {
        EXPECT_STREQ(error.what(), "x must be positive, got -3");
    }
}

TEST(Error, EveryTypeDerivesFromTheRoot) {
    EXPECT_THROW(throw TopologyError("t"), Error);
    EXPECT_THROW(throw NumericalError("n"), Error);
    EXPECT_THROW(throw UnsupportedError("u"), Error);
    EXPECT_THROW(throw InputError("i"), std::runtime_error);
}

TEST(Error, ConcatKeepsFullDoublePrecision) {
    EXPECT_EQ(detail::concat("a", 1, ' ', 0.1), "a1 0.10000000000000001");
}

}  // namespace
}  // namespace limsurf
