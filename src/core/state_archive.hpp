#pragma once
// One function per state-holding type visits every member that changes during a run, for
// saving and for loading alike: `archive(x)` appends x to a byte buffer (StateSaver) or reads it
// back (StateLoader). Writing the member list once keeps save and load from drifting apart.
// Values are stored as their bytes (the state file is read by the same build that wrote it:
// the file's layout hash and build check refuse any other).
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace vdec {

// Found by ordinary lookup from the archives below (argument-dependent lookup sees only std).
template <class A, class T, class U>
void visitState(A& a, std::pair<T, U>& p) {
  a(p.first), a(p.second);
}

class StateSaver {
 public:
  static constexpr bool loading = false;
  template <class T>
  void operator()(const T& value) {
    if constexpr (std::is_trivially_copyable_v<T>) {
      const auto* p = reinterpret_cast<const char*>(&value);
      bytes_.append(p, sizeof(T));
    } else {
      save(value);
    }
  }
  const std::string& bytes() const { return bytes_; }

 private:
  template <class T>
  void save(const std::vector<T>& v) {
    (*this)(static_cast<std::uint64_t>(v.size()));
    if constexpr (std::is_trivially_copyable_v<T>) {
      if (!v.empty()) bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    } else {
      for (const T& item : v) (*this)(item);
    }
  }
  void save(const std::string& s) {
    (*this)(static_cast<std::uint64_t>(s.size()));
    bytes_.append(s);
  }
  template <class T>
  void save(const T& value) {
    visitState(*this, const_cast<T&>(value));
  }
  std::string bytes_;
};

// Thrown when the bytes end early or hold an impossible size: the caller turns it into the
// restart error naming the file.
struct StateFormatError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class StateLoader {
 public:
  static constexpr bool loading = true;
  explicit StateLoader(std::string_view bytes) : bytes_(bytes) {}
  template <class T>
  void operator()(T& value) {
    if constexpr (std::is_trivially_copyable_v<T>) {
      take(&value, sizeof(T));
    } else {
      load(value);
    }
  }
  bool finished() const { return at_ == bytes_.size(); }

 private:
  void take(void* to, std::size_t n) {
    if (n == 0) return;  // an empty vector's data() may be null, which memcpy must not get
    if (n > bytes_.size() - at_) throw StateFormatError("the state ends early");
    std::memcpy(to, bytes_.data() + at_, n);
    at_ += n;
  }
  std::size_t count(std::size_t itemSize) {
    std::uint64_t n = 0;
    (*this)(n);
    if (itemSize > 0 && n > (bytes_.size() - at_) / itemSize) throw StateFormatError("a length beyond the state's end");
    return static_cast<std::size_t>(n);
  }
  template <class T>
  void load(std::vector<T>& v) {
    v.resize(count(std::is_trivially_copyable_v<T> ? sizeof(T) : 1));
    if constexpr (std::is_trivially_copyable_v<T>) {
      take(v.data(), v.size() * sizeof(T));
    } else {
      for (T& item : v) (*this)(item);
    }
  }
  void load(std::string& s) {
    s.resize(count(1));
    take(s.data(), s.size());
  }
  template <class T>
  void load(T& value) {
    visitState(*this, value);
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
};

}  // namespace vdec
