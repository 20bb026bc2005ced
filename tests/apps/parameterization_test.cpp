// Placeholder: filled in by the SEC-applications work (issue 16).
#include <gtest/gtest.h>
