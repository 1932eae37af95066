#pragma once
// Minimal streaming JSON writer: full double precision (%.17g), commas handled, Eigen vectors
// as flat arrays and matrices as arrays of rows. Non-finite numbers are written as null
// because JSON has no NaN/Inf.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "gaitopt/math/decimal.hpp"  // formatDouble, shared by every writer

namespace gaitopt {

class JsonWriter {
 public:
  explicit JsonWriter(bool pretty = true) : pretty_(pretty) {}
  JsonWriter& beginObject();
  JsonWriter& endObject();
  JsonWriter& beginArray();
  JsonWriter& endArray();
  JsonWriter& key(const std::string& k);
  JsonWriter& value(double v);
  JsonWriter& value(int v);
  JsonWriter& value(bool v);
  JsonWriter& value(const std::string& v);
  JsonWriter& value(const char* v) { return value(std::string(v)); }
  JsonWriter& null();
  template <class Derived> JsonWriter& value(const Eigen::MatrixBase<Derived>& m) {
    const bool flat = m.rows() == 1 || m.cols() == 1;
    beginArray();
    if (flat) {
      for (Eigen::Index i = 0; i < m.size(); ++i) value(static_cast<double>(m(i)));
    } else {
      for (Eigen::Index r = 0; r < m.rows(); ++r) {
        beginArray();
        for (Eigen::Index c = 0; c < m.cols(); ++c) value(static_cast<double>(m(r, c)));
        endArray();
      }
    }
    return endArray();
  }
  const std::string& str() const { return out_; }

 private:
  void separate();
  void writeString(const std::string& v);
  void newline();
  std::string out_;
  std::vector<bool> first_;  // per open container: no element written yet
  bool after_key_ = false;
  bool pretty_;
};

}  // namespace gaitopt
