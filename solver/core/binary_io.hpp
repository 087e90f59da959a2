#pragma once
// Binary serialisation of solver state (checkpoints): numbers are stored as their
// bytes, so doubles come back bit for bit. A BinaryReader throws std::runtime_error
// when the data end early, so a truncated file is reported, not misread.

#include <Eigen/Core>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace hfdda {

class BinaryWriter {
 public:
  BinaryWriter() = default;
  /// Writes into `buffer`, emptied first but keeping its capacity (no reallocation when
  /// the same amount is written again).
  explicit BinaryWriter(std::string buffer) : bytes_(std::move(buffer)) { bytes_.clear(); }
  template <class T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>, "put: plain values only");
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  template <class T>
  void put_vector(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>, "put_vector: plain values only");
    put<std::uint64_t>(values.size());
    bytes_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  void put_string(std::string_view text) {
    put<std::uint64_t>(text.size());
    bytes_.append(text.data(), text.size());
  }
  /// Any Eigen matrix of doubles (fixed or dynamic size), with its shape.
  template <class Derived>
  void put_matrix(const Eigen::PlainObjectBase<Derived>& m) {
    static_assert(std::is_same_v<typename Derived::Scalar, double>, "put_matrix: doubles only");
    put<std::int64_t>(m.rows());
    put<std::int64_t>(m.cols());
    bytes_.append(reinterpret_cast<const char*>(m.data()), static_cast<std::size_t>(m.size()) * sizeof(double));
  }
  template <class Derived>
  void put_matrices(const std::vector<Derived>& ms) {
    put<std::uint64_t>(ms.size());
    for (const auto& m : ms) put_matrix(m);
  }
  const std::string& bytes() const { return bytes_; }
  /// The bytes written, moved out (the writer is empty afterwards).
  std::string take_bytes() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

class BinaryReader {
 public:
  explicit BinaryReader(std::string_view bytes) : bytes_(bytes) {}

  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>, "get: plain values only");
    T value;
    std::memcpy(&value, take(sizeof(T)), sizeof(T));
    return value;
  }
  template <class T>
  void get(T& value) { value = get<T>(); }
  template <class T>
  void get_vector(std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>, "get_vector: plain values only");
    const std::uint64_t n = count(sizeof(T));
    values.resize(n);
    if (n > 0) std::memcpy(values.data(), take(n * sizeof(T)), n * sizeof(T));
  }
  std::string get_string() {
    const std::uint64_t n = count(1);
    return std::string(take(n), n);
  }
  template <class Derived>
  void get_matrix(Eigen::PlainObjectBase<Derived>& m) {
    const auto rows = get<std::int64_t>(), cols = get<std::int64_t>();
    if (rows < 0 || cols < 0 || (Derived::RowsAtCompileTime != Eigen::Dynamic && rows != Derived::RowsAtCompileTime) ||
        (Derived::ColsAtCompileTime != Eigen::Dynamic && cols != Derived::ColsAtCompileTime))
      throw std::runtime_error("checkpoint data: matrix of the wrong shape");
    if (static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols) > remaining() / sizeof(double))
      throw std::runtime_error("checkpoint data end early");
    m.resize(rows, cols);
    std::memcpy(m.data(), take(static_cast<std::size_t>(m.size()) * sizeof(double)),
                static_cast<std::size_t>(m.size()) * sizeof(double));
  }
  template <class Derived>
  void get_matrices(std::vector<Derived>& ms) {
    ms.resize(count(16));
    for (auto& m : ms) get_matrix(m);
  }
  /// Throws unless `actual` equals the stored value (sizes that must match the model).
  template <class T>
  void expect(const T& actual, const char* what) {
    if (get<T>() != actual) throw std::runtime_error(std::string("checkpoint does not match the model: ") + what);
  }
  std::size_t remaining() const { return bytes_.size() - position_; }

 private:
  const char* take(std::size_t n) {
    if (n > remaining()) throw std::runtime_error("checkpoint data end early");
    const char* p = bytes_.data() + position_;
    position_ += n;
    return p;
  }
  /// A stored element count, checked against what is left (each element >= `min_bytes`).
  std::uint64_t count(std::size_t min_bytes) {
    const auto n = get<std::uint64_t>();
    if (n > remaining() / min_bytes) throw std::runtime_error("checkpoint data end early");
    return n;
  }
  std::string_view bytes_;
  std::size_t position_ = 0;
};

}  // namespace hfdda
