#pragma once
// numpy <-> library data for the binding: (V, F) arrays read in place into the library's polygon
// soup, Eigen matrices and vectors handed to numpy without a copy, JSON reports as Python dicts.
#include <string>
#include <utility>
#include <vector>

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/string.h>
#include <ricci/mesh/soup.h>
#include <spline/manifold/manifold_space.h>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace msp_python {

namespace nb = nanobind;

/// Any array the caller passes (numpy or anything with __dlpack__ / the buffer protocol).
using AnyArray = nb::ndarray<nb::ro, nb::device::cpu>;
/// An array numpy owns or views.
template <class T>
using NumpyArray = nb::ndarray<nb::numpy, T>;

/// `object` as an array: numpy.asarray(object) (no copy for an array), then its buffer.
/// \throw ricci::InvalidInputError naming `name` when it is not a numeric array.
[[nodiscard]] AnyArray as_array(const nb::handle& object, const char* name);

/// The (V, F) arrays as a polygon soup (V: (n, 3) floats, F: (m, 3) integers in [0, n); any
/// strides, read in place). \throw ricci::InvalidInputError on another shape or dtype, or an
/// index out of range, naming the array and the entry.
[[nodiscard]] ricci::PolygonSoup soup_from_arrays(const nb::handle& V, const nb::handle& F,
                                                  const std::string& source);

/// (n, 3) floats as Eigen rows; (n,) integers; (n, 3) floats whose rows are barycentric
/// coordinates paired with `faces`. \throw ricci::InvalidInputError on another shape or dtype.
[[nodiscard]] Eigen::MatrixX3d matrix_n3(const nb::handle& object, const char* name);
[[nodiscard]] std::vector<int> int_vector(const nb::handle& object, const char* name);
[[nodiscard]] std::vector<spline::DomainPoint> domain_points(const nb::handle& faces,
                                                             const nb::handle& bary);

/// A heap-owned matrix as a numpy array viewing it (freed with the array); Eigen's column-major
/// layout becomes Fortran strides.
template <class Matrix>
NumpyArray<typename Matrix::Scalar> to_numpy(Matrix&& matrix) {
  using M = std::decay_t<Matrix>;
  auto* owned = new M(std::forward<Matrix>(matrix));
  nb::capsule owner(owned, [](void* p) noexcept { delete static_cast<M*>(p); });
  if constexpr (M::ColsAtCompileTime == 1) {
    const size_t shape[1] = {static_cast<size_t>(owned->rows())};
    return NumpyArray<typename M::Scalar>(owned->data(), 1, shape, owner);
  } else {
    const size_t shape[2] = {static_cast<size_t>(owned->rows()),
                             static_cast<size_t>(owned->cols())};
    const int64_t strides[2] = {static_cast<int64_t>(owned->rowStride()),
                                static_cast<int64_t>(owned->colStride())};
    return NumpyArray<typename M::Scalar>(owned->data(), 2, shape, owner, strides);
  }
}

/// A heap-owned std::vector as a numpy array of shape `shape` (its size must match).
template <class T>
NumpyArray<T> vector_to_numpy(std::vector<T>&& values, std::vector<size_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  nb::capsule owner(owned, [](void* p) noexcept { delete static_cast<std::vector<T>*>(p); });
  return NumpyArray<T>(owned->data(), shape.size(), shape.data(), owner);
}

/// A JSON value as the Python object json.loads gives for its text.
[[nodiscard]] nb::object to_python(const nlohmann::json& value);
[[nodiscard]] nb::object to_python(const nlohmann::ordered_json& value);

}  // namespace msp_python
