// A patch's weights at the parameter points met before, for the limit evaluators (internal to the
// limit layer). Most evaluations repeat a handful of points — a quadrature rule's on every face,
// as the sampler places them — so a fixed table of slots keyed by the bits of (u, v), filled first
// come first served and never emptied, spares recomputing them. Entries are published through atomic pointers: readers
// take no lock, and a thread that finds no entry computes the weights itself. A hit returns the
// bits the computation would: no result depends on which thread filled the table, or when.
#pragma once

#include <array>
#include <atomic>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace limsurf::detail {

/// @p Weights: the weights' type (an Eigen matrix), copied in and out of the table.
template <class Weights>
class PointWeightCache {
  public:
    /// @brief @p out = the weights at (@p u, @p v): the table's, or compute(u, v, out)'s (then kept
    ///   while the slots last).
    template <class Compute>
    void weights(double u, double v, Weights& out, Compute&& compute) const {
        const Key key{std::bit_cast<std::uint64_t>(u), std::bit_cast<std::uint64_t>(v)};
        std::uint64_t hash = (key.u * 0x9E3779B97F4A7C15ull) ^ (key.v + 0x632BE59BD9B4E019ull + (key.u << 6));
        hash ^= hash >> 29;
        Slot* empty = nullptr;
        for (std::size_t probe = 0; probe < max_probes; ++probe) {
            Slot& slot = slots_[(hash + probe) % num_slots];
            const Weights* entry = slot.weights.load(std::memory_order_acquire);
            if (entry == nullptr) {
                empty = &slot;
                break;
            }
            if (slot.key == key) {  // written once, before the pointer was published
                out = *entry;
                return;
            }
        }
        compute(u, v, out);
        if (empty != nullptr) {
            const std::lock_guard<std::mutex> lock(mutex_);
            if (empty->weights.load(std::memory_order_relaxed) == nullptr) {  // not taken meanwhile
                owned_.push_back(std::make_unique<Weights>(out));
                empty->key = key;
                empty->weights.store(owned_.back().get(), std::memory_order_release);
            }
        }
    }

  private:
    struct Key {
        std::uint64_t u = 0;
        std::uint64_t v = 0;
        bool operator==(const Key&) const = default;
    };
    // The key beside the pointer: a probe that misses reads no entry (on random points a probe
    // that followed the pointers to compare keys cost a cache miss each).
    struct Slot {
        Key key;
        std::atomic<const Weights*> weights{nullptr};
    };
    static constexpr std::size_t num_slots = 1024;
    static constexpr std::size_t max_probes = 4;
    mutable std::array<Slot, num_slots> slots_{};
    mutable std::mutex mutex_;                             // guards owned_ and the slots' writes
    mutable std::vector<std::unique_ptr<Weights>> owned_;  // what the slots point to
};

}  // namespace limsurf::detail
