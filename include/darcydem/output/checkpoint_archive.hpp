#pragma once
// The binary archive of a checkpoint: the whole state of a run, written when
// it is interrupted (or every so often) and read back by `run --resume`, so
// that the resumed run goes on bit for bit as if it had never stopped.
//
// Each class names its state once, in a member template
//   template <class Archive> void checkpoint(Archive& ar) { ar(a_, b_, ...); }
// which both directions walk: the writer stores the members, the reader loads
// them in the same order. Numbers are stored as the machine holds them; the
// file's header (simulation/run_checkpoint.hpp) says which machine conventions it assumes.
#include <array>
#include <cstdint>
#include <istream>
#include <ostream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace darcydem {

/// A damaged or foreign checkpoint file.
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace checkpoint_detail {

template <class T>
struct is_raw : std::bool_constant<std::is_trivially_copyable_v<T> && !std::is_pointer_v<T>> {};
template <class S, int R, int C, int O, int MR, int MC>
struct is_raw<Eigen::Matrix<S, R, C, O, MR, MC>> : std::bool_constant<(R > 0 && C > 0)> {};
template <class T, std::size_t N>
struct is_raw<std::array<T, N>> : is_raw<T> {};

template <class T>
struct is_vector : std::false_type {};
template <class T, class A>
struct is_vector<std::vector<T, A>> : std::true_type {};

template <class T>
struct is_array : std::false_type {};
template <class T, std::size_t N>
struct is_array<std::array<T, N>> : std::true_type {};

template <class T>
struct is_pair : std::false_type {};
template <class A, class B>
struct is_pair<std::pair<A, B>> : std::true_type {};

}  // namespace checkpoint_detail

/// Loading = false writes to a std::ostream, true reads from a std::istream.
template <bool Loading>
class CheckpointArchive {
 public:
  static constexpr bool loading = Loading;
  using Stream = std::conditional_t<Loading, std::istream, std::ostream>;

  /// `name` is the file, for messages.
  CheckpointArchive(Stream& stream, std::string name) : stream_(stream), name_(std::move(name)) {}

  template <class... T>
  void operator()(T&... x) {
    (item(x), ...);
  }

  [[nodiscard]] const std::string& name() const { return name_; }

 private:
  void bytes(void* p, std::size_t n) {
    if (n == 0) return;
    if constexpr (Loading) {
      stream_.read(static_cast<char*>(p), static_cast<std::streamsize>(n));
      if (stream_.gcount() != static_cast<std::streamsize>(n))
        throw CheckpointError(name_ + ": the file ends early (truncated or damaged)");
    } else {
      stream_.write(static_cast<const char*>(p), static_cast<std::streamsize>(n));
      if (!stream_) throw std::runtime_error(name_ + ": cannot write the checkpoint");
    }
  }

  /// A length, checked against what could possibly follow on reading.
  std::size_t length(std::size_t n, std::size_t element_bytes) {
    auto stored = static_cast<std::uint64_t>(n);
    bytes(&stored, sizeof stored);
    if constexpr (Loading) {
      constexpr std::uint64_t limit = std::uint64_t{1} << 40;  // 1 TiB: no real state is larger
      if (stored > limit / (element_bytes > 0 ? element_bytes : 1))
        throw CheckpointError(name_ + ": an array length is impossible (truncated or damaged)");
    }
    return static_cast<std::size_t>(stored);
  }

  template <class T>
  void item(T& x) {
    using namespace checkpoint_detail;
    if constexpr (requires { x.checkpoint(*this); }) {
      x.checkpoint(*this);
    } else if constexpr (is_raw<T>::value) {
      bytes(&x, sizeof x);
    } else if constexpr (std::is_same_v<T, std::string>) {
      const std::size_t n = length(x.size(), 1);
      if constexpr (Loading) x.resize(n);
      bytes(x.data(), n);
    } else if constexpr (std::is_same_v<T, Eigen::VectorXd>) {
      const std::size_t n = length(static_cast<std::size_t>(x.size()), sizeof(double));
      if constexpr (Loading) x.resize(static_cast<Eigen::Index>(n));
      bytes(x.data(), n * sizeof(double));
    } else if constexpr (is_vector<T>::value) {
      using E = typename T::value_type;
      const std::size_t n = length(x.size(), sizeof(E));
      if constexpr (Loading) x.resize(n);
      if constexpr (is_raw<E>::value) {
        bytes(x.data(), n * sizeof(E));
      } else {
        for (auto& e : x) item(e);
      }
    } else if constexpr (is_array<T>::value) {
      for (auto& e : x) item(e);
    } else if constexpr (is_pair<T>::value) {
      item(x.first);
      item(x.second);
    } else {
      static_assert(sizeof(T) == 0,
                    "no checkpoint rule for this type: give it a checkpoint(Archive&) member");
    }
  }

  Stream& stream_;
  std::string name_;
};

using CheckpointWriter = CheckpointArchive<false>;
using CheckpointReader = CheckpointArchive<true>;

}  // namespace darcydem
