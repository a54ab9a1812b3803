// The eraser's two containers: an indexed heap of nodes by key (the queue of the paper model's
// erase, the keys of every erase), and an append-only pool in chunks (the erase records).
#pragma once

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tinlod::erase {

// Indexed binary min-heap of nodes by key.
class NodeHeap {
  public:
    void reset(std::size_t nodes) {
        key_.assign(nodes, 0.0f);
        pos_.assign(nodes, -1);
        heap_.clear();
    }
    bool empty() const { return heap_.empty(); }
    bool contains(std::uint32_t v) const { return pos_[v] >= 0; }
    std::uint32_t top() const { return heap_.front(); }
    // Smallest key below the top (+inf when the top is alone).
    float second_key() const {
        float k = INFINITY;
        for (std::size_t c = 1; c < std::min<std::size_t>(3, heap_.size()); ++c)
            k = std::min(k, key_[heap_[c]]);
        return k;
    }
    // Builds the heap at once from the nodes whose key was stored with store_key.
    void build(std::vector<std::uint32_t> nodes) {
        heap_ = std::move(nodes);
        for (std::size_t i = 0; i < heap_.size(); ++i)
            pos_[heap_[i]] = std::int32_t(i);
        for (std::size_t i = heap_.size() / 2; i-- > 0;)
            down(std::int32_t(i));
    }
    float key(std::uint32_t v) const { return key_[v]; }
    bool has_key(std::uint32_t v) const { return v < key_.size(); }
    void store_key(std::uint32_t v, float key) { key_[v] = key; } // for a node outside the heap
    void set(std::uint32_t v, float key) {
        if (pos_[v] < 0) {
            key_[v] = key;
            pos_[v] = std::int32_t(heap_.size());
            heap_.push_back(v);
            up(pos_[v]);
            return;
        }
        const float old = key_[v];
        key_[v] = key;
        if (key < old)
            up(pos_[v]);
        else
            down(pos_[v]);
    }
    // Frees the queue, keeping every stored key (store_key and key work until the next reset).
    void release_queue() {
        std::vector<std::int32_t>().swap(pos_);
        std::vector<std::uint32_t>().swap(heap_);
    }
    // Frees the keys too (until the next reset).
    void release() {
        std::vector<float>().swap(key_);
        release_queue();
    }
    void pop() {
        const std::uint32_t v = heap_.front();
        pos_[v] = -1;
        const std::uint32_t last = heap_.back();
        heap_.pop_back();
        if (heap_.empty())
            return;
        heap_[0] = last;
        pos_[last] = 0;
        down(0);
    }
    std::size_t bytes() const {
        return key_.capacity() * 4 + pos_.capacity() * 4 + heap_.capacity() * 4;
    }

  private:
    void up(std::int32_t i) {
        const std::uint32_t v = heap_[i];
        while (i > 0) {
            const std::int32_t p = (i - 1) / 2;
            if (!(key_[v] < key_[heap_[p]]))
                break;
            heap_[i] = heap_[p];
            pos_[heap_[i]] = i;
            i = p;
        }
        heap_[i] = v;
        pos_[v] = i;
    }
    void down(std::int32_t i) {
        const std::uint32_t v = heap_[i];
        const std::int32_t n = std::int32_t(heap_.size());
        for (;;) {
            std::int32_t c = 2 * i + 1;
            if (c >= n)
                break;
            if (c + 1 < n && key_[heap_[c + 1]] < key_[heap_[c]])
                ++c;
            if (!(key_[heap_[c]] < key_[v]))
                break;
            heap_[i] = heap_[c];
            pos_[heap_[i]] = i;
            i = c;
        }
        heap_[i] = v;
        pos_[v] = i;
    }
    std::vector<float> key_;
    std::vector<std::int32_t> pos_;
    std::vector<std::uint32_t> heap_;
};

// An append-only array in chunks of 2^20 entries. It grows without moving what it holds (the
// history is most of a refiner's memory, and a vector's reallocation copied all of it in one
// frame: docs/decisions/005-chunked-history-pool.md), and the entries one append takes never
// straddle two chunks, so run() sees them contiguous.
template <class T> class ChunkedPool {
  public:
    static constexpr std::size_t k_shift = 20, k_chunk = std::size_t(1) << k_shift;

    T &operator[](std::size_t i) { return chunks_[i >> k_shift][i & (k_chunk - 1)]; }
    const T &operator[](std::size_t i) const { return chunks_[i >> k_shift][i & (k_chunk - 1)]; }
    // The entries from i on that one append took.
    const T *run(std::size_t i) const { return &(*this)[i]; }
    // The index space in use (a chunk's unused tail counts when an append moved on).
    std::size_t size() const { return size_; }
    // Appends n value-initialised entries (n <= k_chunk) in one chunk; returns the first's index.
    std::size_t append(std::size_t n) {
        assert(n <= k_chunk);
        if (chunks_.empty() || chunks_.back().size() + n > k_chunk) {
            size_ = chunks_.size() << k_shift;
            chunks_.emplace_back();
        }
        std::vector<T> &last = chunks_.back();
        if (last.size() + n > last.capacity()) // doubling inside the chunk only
            last.reserve(std::min(k_chunk, std::max(2 * last.capacity(), last.size() + n)));
        last.resize(last.size() + n);
        const std::size_t first = size_;
        size_ += n;
        return first;
    }
    void shrink_to_fit() {
        if (!chunks_.empty())
            chunks_.back().shrink_to_fit();
    }
    std::size_t bytes() const {
        std::size_t b = chunks_.capacity() * sizeof(std::vector<T>);
        for (const std::vector<T> &c : chunks_)
            b += c.capacity() * sizeof(T);
        return b;
    }

  private:
    std::vector<std::vector<T>> chunks_;
    std::size_t size_ = 0;
};

} // namespace tinlod::erase
