#pragma once
// numpy arrays and Python sequences as the module's C++ sees them: a vector
// as a 1-d array, rows of numbers as a 2-d array that owns them, a sequence
// as a vector (named in the error when it is not one), and the CSV rows a
// run wrote (its dense output) as a 2-d array.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <sympl/core/error.hpp>

namespace sympl::app::python {

namespace py = pybind11;

inline py::array_t<double> array_of(const std::vector<double>& v) {
    py::array_t<double> a(py::ssize_t(v.size()));
    std::copy(v.begin(), v.end(), a.mutable_data());
    return a;
}

// Rows of `columns` numbers as a 2-d array that owns them: no copy.
inline py::array_t<double> array_of(std::vector<double>&& v, std::size_t columns) {
    auto owned = std::make_unique<std::vector<double>>(std::move(v));
    std::vector<double>* held = owned.get();
    const py::capsule owner(held, [](void* p) { delete static_cast<std::vector<double>*>(p); });
    owned.release();  // the capsule owns it now
    const std::size_t rows = columns ? held->size() / columns : 0;
    return py::array_t<double>({py::ssize_t(rows), py::ssize_t(columns)},
                               {py::ssize_t(columns * sizeof(double)), py::ssize_t(sizeof(double))}, held->data(),
                               owner);
}

inline std::vector<double> vector_of(const py::handle& h, const char* what) {
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(h);
    if (!a || a.ndim() != 1)
        throw invalid_argument(std::string(what) + ": expected a one-dimensional sequence of numbers");
    return std::vector<double>(a.data(), a.data() + a.size());
}

// Rows of numbers a run wrote as CSV text (its trajectory), as a 2-d array.
inline py::array_t<double> rows_of(const std::string& csv, std::size_t columns) {
    std::vector<double> values;
    const char* at = csv.c_str();
    while (*at) {
        char* end = nullptr;
        values.push_back(std::strtod(at, &end));
        at = end;
        while (*at == ',' || *at == '\n') ++at;
    }
    const std::size_t rows = columns ? values.size() / columns : 0;
    py::array_t<double> a({py::ssize_t(rows), py::ssize_t(columns)});
    std::copy(values.begin(), values.begin() + std::ptrdiff_t(rows * columns), a.mutable_data());
    return a;
}

}  // namespace sympl::app::python
