#pragma once
/// \file record_log.hpp
/// Records that carry state vectors (an impact's x, v and v after it, a
/// sample's x and v), stored flat: each record's scalars in one array, its
/// vectors, all of one length, end to end in another. Appending allocates
/// nothing (amortised). A std::vector of records with Eigen::VectorXd
/// members allocated every vector: in a 2-DOF run recording its impacts
/// and stroboscopic points, five allocations per impact and a third of the
/// run's time with their page faults (docs/performance.md).
///
/// Reading gives views (RecordLayout<Record>::View): the record's scalars
/// by value and its vectors as Eigen::Maps into the log, valid until the
/// log is next appended to; View::Owned() copies one into a Record.

#include <Eigen/Dense>
#include <array>
#include <cstddef>
#include <vector>

#include "impactkit/core/errors.hpp"
#include "impactkit/core/large_buffer_allocator.hpp"

namespace impactkit {

/// Specialised for each recorded type: Scalars (the record without its
/// vectors), kVectors, View, and
///   static Scalars ScalarsOf(const Record&);
///   static std::array<const Eigen::VectorXd*, kVectors> VectorsOf(const Record&);
///   static View MakeView(const Scalars&, const double* vectors, Eigen::Index length);
template <class Record>
struct RecordLayout;

template <class Record>
class RecordLog {
  using Layout = RecordLayout<Record>;

 public:
  using View = typename Layout::View;

  /// Appends a copy. Throws InvalidInput if its vectors' length differs
  /// from the first record's.
  void push_back(const Record& record) {
    const std::array<const Eigen::VectorXd*, Layout::kVectors> vectors = Layout::VectorsOf(record);
    const Eigen::Index length = scalars_.empty() ? vectors[0]->size() : length_;
    for (const Eigen::VectorXd* v : vectors) {
      if (v->size() != length) {
        throw InvalidInput("RecordLog: every recorded vector must have one length");
      }
    }
    if (scalars_.empty()) values_.reserve(reserved_ * Layout::kVectors * length);
    length_ = length;
    for (const Eigen::VectorXd* v : vectors) {
      values_.insert(values_.end(), v->data(), v->data() + length_);
    }
    scalars_.push_back(Layout::ScalarsOf(record));
  }

  /// Room for `records` records without growing (asked before the first
  /// record, the room for their vectors waits for its length): a long
  /// run's records then fault each page in once, where growing by
  /// doubling faults in about twice their size.
  void reserve(std::size_t records) {
    scalars_.reserve(records);
    reserved_ = records;
    if (!scalars_.empty()) values_.reserve(records * Layout::kVectors * length_);
  }

  std::size_t size() const { return scalars_.size(); }
  bool empty() const { return scalars_.empty(); }
  View operator[](std::size_t i) const {
    return Layout::MakeView(scalars_[i], values_.data() + i * Layout::kVectors * length_, length_);
  }
  View front() const { return (*this)[0]; }
  View back() const { return (*this)[size() - 1]; }

  class Iterator {
   public:
    using value_type = View;
    using difference_type = std::ptrdiff_t;
    Iterator() = default;
    Iterator(const RecordLog* log, std::size_t index) : log_(log), index_(index) {}
    View operator*() const { return (*log_)[index_]; }
    Iterator& operator++() {
      ++index_;
      return *this;
    }
    Iterator operator++(int) {
      Iterator before = *this;
      ++index_;
      return before;
    }
    bool operator==(const Iterator& other) const = default;

   private:
    const RecordLog* log_ = nullptr;
    std::size_t index_ = 0;
  };
  Iterator begin() const { return {this, 0}; }
  Iterator end() const { return {this, size()}; }

 private:
  std::vector<typename Layout::Scalars, LargeBufferAllocator<typename Layout::Scalars>> scalars_;
  /// Record i's vectors at [i kVectors length, (i + 1) kVectors length).
  std::vector<double, LargeBufferAllocator<double>> values_;
  Eigen::Index length_ = 0;
  std::size_t reserved_ = 0;
};

}  // namespace impactkit
