// One row of a sparse matrix summed column by column with a dense accumulator (Gustavson's
// algorithm), then written out sorted: the inner loop of every row-by-row assembly (element_gather.h,
// the vector-field design's sums of products). Private: any layer.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "limsurf/core/types.h"

namespace limsurf::detail {

class RowAccumulator {
  public:
    /// @param cols the columns a row may have (column indices below it)
    explicit RowAccumulator(Index cols)
        : sum_(static_cast<std::size_t>(cols), 0.0), row_of_(static_cast<std::size_t>(cols), invalid_index) {}

    /// Adds @p value to column @p col of the current row; repeated columns sum in the order they come.
    void add(Index col, double value) {
        const auto at = static_cast<std::size_t>(col);
        if (row_of_[at] != row_) {
            row_of_[at] = row_;
            sum_[at] = value;
            touched_.push_back(col);
        } else {
            sum_[at] += value;
        }
    }

    /// @brief Appends the current row's columns (ascending) and sums to @p columns and @p values,
    ///   structural zeros kept, and starts the next row. @return the row's number of entries
    /// On a first row, reserves room for @p rows_expected rows of about its size (rows of a mesh's
    /// operators have about as many entries: no doubling copies).
    template <class Columns, class Values>
    Index flush(Columns& columns, Values& values, std::size_t rows_expected) {
        std::sort(touched_.begin(), touched_.end());
        if (columns.empty()) {
            const std::size_t room = rows_expected * (touched_.size() + touched_.size() / 4 + 1);
            columns.reserve(room);
            values.reserve(room);
        }
        for (const Index c : touched_) {
            columns.push_back(c);
            values.push_back(sum_[static_cast<std::size_t>(c)]);
        }
        const auto count = static_cast<Index>(touched_.size());
        touched_.clear();
        ++row_;
        return count;
    }

  private:
    std::vector<double> sum_;
    std::vector<Index> row_of_;  ///< per column: the row whose sum it holds
    std::vector<Index> touched_;
    Index row_ = 0;
};

}  // namespace limsurf::detail
