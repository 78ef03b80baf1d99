// phasmid petab CONFIG -o DIR [--data TRIAL] [--parameters PARAMS.tsv] [--set K=V]: a recording
// fit as PEtab tables (docs/recordings.md, "PEtab tables"): DIR/parameters.tsv,
// conditions.tsv, observables.tsv, measurements.tsv and problem.yaml naming them. The files
// are written under temporary names and renamed only when all are written, so a failure
// leaves none of them.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "app/options.hpp"
#include "app/verb.hpp"
#include "common/error.hpp"
#include "config/config.hpp"
#include "config/fit_section.hpp"
#include "fit/parameter_table.hpp"
#include "fit/petab_tables.hpp"

namespace phasmid::app {
namespace {
struct PetabArgs {
  std::string config, out;
  std::vector<std::string> sets;
  fit::FitOverrides ov;
  bool quiet = false;
};

const char* kProblem =
    "# PEtab problem of a phasmid recording fit (docs/recordings.md, \"PEtab tables\"). The model is\n"
    "# the phasmid config's, not SBML; its names are phasmid's (dotted).\n"
    "format_version: 1\n"
    "parameter_file: parameters.tsv\n"
    "problems:\n"
    "  - sbml_files: []\n"
    "    condition_files: [conditions.tsv]\n"
    "    measurement_files: [measurements.tsv]\n"
    "    observable_files: [observables.tsv]\n";

// Writes every file as "<name>.tmp" first; renames them all once all are written.
void write_all(const std::string& dir, const std::vector<std::pair<std::string, std::string>>& files) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error(dir + ": cannot create the directory: " + ec.message());
  auto remove_tmps = [&] {
    for (const auto& f : files) std::remove((dir + "/" + f.first + ".tmp").c_str());
  };
  for (const auto& [name, text] : files) {
    const std::string tmp = dir + "/" + name + ".tmp";
    std::ofstream os(tmp, std::ios::binary | std::ios::trunc);
    os.write(text.data(), static_cast<std::streamsize>(text.size()));
    os.close();
    if (!os) {
      remove_tmps();
      throw Error("cannot write " + tmp);
    }
  }
  for (const auto& f : files) {
    std::filesystem::rename(dir + "/" + f.first + ".tmp", dir + "/" + f.first, ec);
    if (ec) {
      remove_tmps();
      throw Error("cannot rename " + dir + "/" + f.first + ".tmp: " + ec.message());
    }
  }
}

int run(const PetabArgs& a) {
  fit::check_overrides(a.ov);
  config::Config cfg = config::load_config(a.config);
  auto scenario = config::build_scenario(cfg, a.sets);
  const fit::FitSpec spec = config::fit_spec(cfg, *scenario, a.ov);
  const fit::PetabTables t = fit::format_petab(spec.targets, spec.conditions);
  write_all(a.out, {{"parameters.tsv", fit::format_parameter_table(spec.parameters)},
                    {"conditions.tsv", t.conditions},
                    {"observables.tsv", t.observables},
                    {"measurements.tsv", t.measurements},
                    {"problem.yaml", kProblem}});
  if (!a.quiet) std::cerr << "phasmid petab: -> " << a.out << "/problem.yaml (and its four tables)\n";
  return 0;
}

const RegisterVerb reg{{"petab", "Write a recording fit as PEtab tables (parameters, conditions, observables, measurements)",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<PetabArgs>();
                          add_config_arg(sub, a->config, "scenario config (TOML) with a [fit] section and [[fit.recording]]");
                          sub.add_option("--data", a->ov.data, "the recording, replacing the config's one");
                          sub.add_option("--parameters", a->ov.parameters, "PEtab parameter table (TSV)");
                          sub.add_option("-o,--output", a->out, "directory for the tables")->required();
                          add_sets(sub, a->sets);
                          add_quiet(sub, a->quiet);
                          return std::function<int()>([a] { return run(*a); });
                        }}};
}  // namespace
}  // namespace phasmid::app
