#include "arrays.h"

#include <cstdint>

#include <ricci/mesh/errors.h>

namespace msp_python {
namespace {

std::string shape_text(const AnyArray& a) {
  std::string text = "(";
  for (size_t i = 0; i < a.ndim(); ++i) text += (i ? ", " : "") + std::to_string(a.shape(i));
  return text + (a.ndim() == 1 ? ",)" : ")");
}

bool is_float(const nb::dlpack::dtype& t) {
  return t.code == static_cast<uint8_t>(nb::dlpack::dtype_code::Float) &&
         (t.bits == 32 || t.bits == 64);
}

bool is_integer(const nb::dlpack::dtype& t) {
  return (t.code == static_cast<uint8_t>(nb::dlpack::dtype_code::Int) ||
          t.code == static_cast<uint8_t>(nb::dlpack::dtype_code::UInt)) &&
         (t.bits == 8 || t.bits == 16 || t.bits == 32 || t.bits == 64);
}

void check_shape(const AnyArray& a, const char* name, size_t ndim, int64_t columns) {
  if (a.ndim() != ndim || (columns >= 0 && a.shape(1) != static_cast<size_t>(columns))) {
    throw ricci::InvalidInputError(std::string(name) + " must have shape " +
                                   (ndim == 1 ? "(n,)" : "(n, " + std::to_string(columns) + ")") +
                                   ", not " + shape_text(a));
  }
}

// Element (i, j) of a 1-D or 2-D array of type T, by strides (counted in elements).
template <class T>
T at(const AnyArray& a, size_t i, size_t j = 0) {
  const auto* data = static_cast<const T*>(a.data());
  return data[static_cast<int64_t>(i) * a.stride(0) +
              (a.ndim() > 1 ? static_cast<int64_t>(j) * a.stride(1) : 0)];
}

double float_at(const AnyArray& a, size_t i, size_t j) {
  return a.dtype().bits == 64 ? at<double>(a, i, j) : at<float>(a, i, j);
}

// Integers of any width and signedness, as int64 (uint64 above 2^63 shows as negative: refused
// by the range checks like any other negative index).
int64_t int_at(const AnyArray& a, size_t i, size_t j = 0) {
  const bool is_signed = a.dtype().code == static_cast<uint8_t>(nb::dlpack::dtype_code::Int);
  switch (a.dtype().bits) {
    case 8:
      return is_signed ? at<int8_t>(a, i, j) : at<uint8_t>(a, i, j);
    case 16:
      return is_signed ? at<int16_t>(a, i, j) : at<uint16_t>(a, i, j);
    case 32:
      return is_signed ? at<int32_t>(a, i, j) : at<uint32_t>(a, i, j);
    default:
      return is_signed ? at<int64_t>(a, i, j) : static_cast<int64_t>(at<uint64_t>(a, i, j));
  }
}

AnyArray float_array(const nb::handle& object, const char* name, size_t ndim, int64_t columns) {
  AnyArray a = as_array(object, name);
  if (!is_float(a.dtype()))
    throw ricci::InvalidInputError(std::string(name) + " must hold float64 or float32 numbers");
  check_shape(a, name, ndim, columns);
  return a;
}

AnyArray integer_array(const nb::handle& object, const char* name, size_t ndim, int64_t columns) {
  AnyArray a = as_array(object, name);
  if (!is_integer(a.dtype()))
    throw ricci::InvalidInputError(std::string(name) + " must hold integers");
  check_shape(a, name, ndim, columns);
  return a;
}

}  // namespace

AnyArray as_array(const nb::handle& object, const char* name) {
  nb::object array = nb::module_::import_("numpy").attr("asarray")(object);
  AnyArray result;
  if (!nb::try_cast(array, result))
    throw ricci::InvalidInputError(std::string(name) + " must be a numeric array");
  return result;
}

ricci::PolygonSoup soup_from_arrays(const nb::handle& V, const nb::handle& F,
                                    const std::string& source) {
  const AnyArray v = float_array(V, "V", 2, 3);
  const AnyArray f = integer_array(F, "F", 2, 3);
  ricci::PolygonSoup soup;
  soup.source = source;
  soup.positions.resize(v.shape(0));
  for (size_t i = 0; i < v.shape(0); ++i)
    for (size_t k = 0; k < 3; ++k)
      soup.positions[i][static_cast<Eigen::Index>(k)] = float_at(v, i, k);
  const auto n = static_cast<int64_t>(v.shape(0));
  soup.faces.resize(f.shape(0));
  for (size_t i = 0; i < f.shape(0); ++i) {
    auto& face = soup.faces[i];
    face.resize(3);
    for (size_t k = 0; k < 3; ++k) {
      const int64_t index = int_at(f, i, k);
      if (index < 0 || index >= n) {
        throw ricci::InvalidInputError("F[" + std::to_string(i) + ", " + std::to_string(k) +
                                       "] = " + std::to_string(index) +
                                       " is not a vertex index in [0, " + std::to_string(n) + ")");
      }
      face[k] = static_cast<int>(index);
    }
  }
  return soup;
}

Eigen::MatrixX3d matrix_n3(const nb::handle& object, const char* name) {
  const AnyArray a = float_array(object, name, 2, 3);
  Eigen::MatrixX3d m(static_cast<Eigen::Index>(a.shape(0)), 3);
  for (size_t i = 0; i < a.shape(0); ++i)
    for (size_t k = 0; k < 3; ++k)
      m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) = float_at(a, i, k);
  return m;
}

std::vector<int> int_vector(const nb::handle& object, const char* name) {
  const AnyArray a = integer_array(object, name, 1, -1);
  std::vector<int> values(a.shape(0));
  for (size_t i = 0; i < a.shape(0); ++i) {
    const int64_t x = int_at(a, i);
    if (x < INT32_MIN || x > INT32_MAX)
      throw ricci::InvalidInputError(std::string(name) + "[" + std::to_string(i) +
                                     "] is out of range");
    values[i] = static_cast<int>(x);
  }
  return values;
}

std::vector<spline::DomainPoint> domain_points(const nb::handle& faces, const nb::handle& bary) {
  const std::vector<int> face = int_vector(faces, "faces");
  const Eigen::MatrixX3d b = matrix_n3(bary, "bary");
  if (static_cast<Eigen::Index>(face.size()) != b.rows()) {
    throw ricci::InvalidInputError("faces and bary must have as many rows (" +
                                   std::to_string(face.size()) + " and " +
                                   std::to_string(b.rows()) + ")");
  }
  std::vector<spline::DomainPoint> points(face.size());
  for (size_t i = 0; i < face.size(); ++i)
    points[i] = {face[i], b.row(static_cast<Eigen::Index>(i)).transpose()};
  return points;
}

nb::object to_python(const nlohmann::json& value) {
  return nb::module_::import_("json").attr("loads")(value.dump());
}

nb::object to_python(const nlohmann::ordered_json& value) {
  return nb::module_::import_("json").attr("loads")(value.dump());
}

}  // namespace msp_python
