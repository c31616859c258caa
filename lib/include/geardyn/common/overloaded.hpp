/// @file
/// @brief Overloaded: the lambda-set visitor for std::visit over geardyn's closed variants
/// (θ-coefficients, mesh cores). Write one lambda per alternative and no catch-all, so that a
/// forgotten alternative fails to compile (architecture §3.4).
#pragma once

namespace geardyn {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

}  // namespace geardyn
