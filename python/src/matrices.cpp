// The system matrices (matrices_export.hpp) as CSC triples for scipy.sparse and complex dense
// numpy arrays, with the DOF map and dofs.json's report.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <optional>

#include "bindings.hpp"
#include "geardyn/matrices_export.hpp"

namespace geardyn::python {
namespace {

// (data, indices, indptr, shape) of a compressed column matrix: scipy.sparse.csc_matrix's input.
py::tuple Csc(SparseMatrix a) {
  a.makeCompressed();
  const auto nnz = static_cast<py::ssize_t>(a.nonZeros());
  py::array_t<double> data(nnz);
  py::array_t<int> indices(nnz);
  py::array_t<int> indptr(a.outerSize() + 1);
  std::copy(a.valuePtr(), a.valuePtr() + nnz, data.mutable_data());
  std::copy(a.innerIndexPtr(), a.innerIndexPtr() + nnz, indices.mutable_data());
  std::copy(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1, indptr.mutable_data());
  return py::make_tuple(data, indices, indptr, py::make_tuple(a.rows(), a.cols()));
}

}  // namespace

void BindMatrices(py::module_& m) {
  m.def(
      "system_matrices",
      [](const Scene& scene, int harmonics, const std::string& out_dir) {
        std::optional<app::SystemMatrices> x;
        {
          py::gil_scoped_release release;
          x.emplace(app::ExportSystemMatrices(scene, harmonics));
          if (!out_dir.empty()) app::WriteSystemMatrices(*x, out_dir);
        }
        py::dict d;
        d["report"] = ToPython(x->report);
        d["mass"] = Csc(x->mean.mass);
        d["damping"] = Csc(x->mean.damping);
        d["stiffness"] = Csc(x->mean.stiffness);
        d["mean_load"] = VectorX(x->mean_load);
        py::list k, c, f;
        for (int i = 0; i <= x->harmonics.num_harmonics(); ++i) {
          k.append(MatrixXc(x->harmonics.stiffness[i]));
          c.append(MatrixXc(x->harmonics.damping[i]));
          f.append(VectorXc(x->harmonics.load[i]));
        }
        d["stiffness_harmonics"] = k;
        d["damping_harmonics"] = c;
        d["load_harmonics"] = f;
        return d;
      },
      py::arg("scene"), py::arg("harmonics"), py::arg("out_dir"));
}

}  // namespace geardyn::python
