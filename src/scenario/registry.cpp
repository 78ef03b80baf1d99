#include "scenario/registry.hpp"

#include "common/error.hpp"
#include "common/nearest.hpp"

namespace phasmid::scenario {

#define PHASMID_MODEL_KIND(factory) ModelKind factory();
#define PHASMID_TEST_PROBLEM(factory) ModelKind factory();
#include "scenario/kinds/builtin_kinds.def"
#undef PHASMID_MODEL_KIND
#undef PHASMID_TEST_PROBLEM

namespace {
std::vector<ModelKind>& registry() {
  static std::vector<ModelKind> kinds = [] {
    std::vector<ModelKind> k;
#define PHASMID_MODEL_KIND(factory) k.push_back(factory());
#define PHASMID_TEST_PROBLEM(factory) \
  k.push_back(factory());             \
  k.back().category = KindCategory::TestProblem;
#include "scenario/kinds/builtin_kinds.def"
#undef PHASMID_MODEL_KIND
#undef PHASMID_TEST_PROBLEM
    return k;
  }();
  return kinds;
}
}  // namespace

const std::vector<ModelKind>& model_kinds() { return registry(); }

std::string category_name(KindCategory c) { return c == KindCategory::TestProblem ? "test_problem" : "model"; }

RegisterModelKind::RegisterModelKind(ModelKind kind) { registry().push_back(std::move(kind)); }

const ModelKind& model_kind(const std::string& name) {
  std::vector<std::string> names;
  for (const ModelKind& k : registry()) {
    if (k.name == name) return k;
    names.push_back(k.name);
  }
  std::string list, near = nearest(name, names);
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  throw Error("unknown model type '" + name + "'" + (near.empty() ? "" : " (did you mean '" + near + "'?)") +
              "; the model types are " + list);
}

std::string ModelSection::choice(const std::string& key, const std::string& fallback,
                                 const std::vector<std::string>& allowed) const {
  std::string v = text(key, fallback), list;
  for (const auto& a : allowed) {
    if (a == v) return v;
    list += (list.empty() ? "\"" : ", \"") + a + "\"";
  }
  throw Error(where(key) + ": " + key + " must be one of " + list + " (got \"" + v + "\")");
}

}  // namespace phasmid::scenario
