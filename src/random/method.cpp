// The method name table (antcd/method.hpp).
#include <antcd/error.hpp>
#include <antcd/method.hpp>

#include <string>

namespace antcd {
namespace {

struct MethodNames {
  Method method;
  std::string_view name;
  std::string_view label;
};

constexpr MethodNames kNames[] = {
    {Method::Exact, "exact", "Exact"},
    {Method::SphereObb, "sphere-obb", "Sphere-OBB"},
    {Method::Aco, "aco", "ACO"},
    {Method::Maco, "maco", "MACO"},
    {Method::Pso, "pso", "PSO"},
    {Method::Ga, "ga", "GA"},
    {Method::Exhaustive, "exhaustive", "Exhaustive"},
    {Method::Grid, "grid", "Grid"},
};

const MethodNames* find(Method m) {
  for (const MethodNames& n : kNames) {
    if (n.method == m) return &n;
  }
  return nullptr;
}

}  // namespace

std::string_view method_name(Method m) {
  const MethodNames* n = find(m);
  return n != nullptr ? n->name : "?";
}

std::string_view method_label(Method m) {
  const MethodNames* n = find(m);
  return n != nullptr ? n->label : "?";
}

Method parse_method(std::string_view name) {
  std::string accepted;
  for (const MethodNames& n : kNames) {
    if (n.name == name) return n.method;
    accepted += (accepted.empty() ? "" : ", ") + std::string(n.name);
  }
  throw ArgumentError("unknown method '" + std::string(name) + "' (expected one of " + accepted +
                      ")");
}

}  // namespace antcd
