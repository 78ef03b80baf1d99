// phasmid demo [-o DIR]: the main job on embedded defaults. It runs the real verbs of this
// same binary, one after another, so the demo exercises exactly what users run:
//   simulate the single FTi joint network, fit the FTi mechanics to Section 3.1's targets,
//   compute the sensitivities of the network's steady gait to all its parameters, run a small intersegmental-coupling sweep and a
//   small global sensitivity analysis, and write one HTML report per HDF5 file.
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "app/verb.hpp"
#include "common/embedded.hpp"
#include "common/error.hpp"
#include "io/output_path.hpp"

namespace phasmid::app {
namespace {
namespace fs = std::filesystem;

struct DemoStep {
  const char* verb;
  const char* config;  // embedded config name
  const char* output;  // file name in the demo directory
  const char* what;
};

const DemoStep kSteps[] = {
    {"simulate", "configs/single_joint_fti.toml", "single_joint_fti.h5",
     "isolated FTi joint network (Fig. 2.12, Section 3.1.2): 9 s of walking"},
    {"fit", "configs/fit_fti_section31.toml", "fit_fti_section31.h5",
     "spring constants of the FTi joint fitted to Section 3.1's switch conditions (2.42)"},
    {"sensitivity", "configs/sensitivity_steady_gait.toml", "sensitivity_steady_gait.h5",
     "sensitivities of the FTi network's steady gait (period, phase ratio, extremal angles) to all its parameters"},
    {"sweep", "configs/demo_coupling_sweep.toml", "demo_coupling_sweep.h5",
     "small sweep of the intersegmental coupling of the three-leg network"},
    {"gsa", "configs/gsa_single_joint.toml", "gsa_single_joint.h5",
     "Sobol' indices of the FTi network's period and extremal angles over its three drives (rate motoneurons), N = 1024"},
};

std::string self_path() {
  std::error_code ec;
  fs::path p = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw Error("demo: cannot locate the phasmid binary (/proc/self/exe)");
  return p.string();
}

int run_child(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = fork();
  if (pid < 0) throw Error("demo: fork failed");
  if (pid == 0) {
    execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

int run_demo(const std::string& dir_arg) {
  fs::path dir = dir_arg.empty() ? fs::path("demo_output") : fs::path(dir_arg);
  io::check_output_directory(dir.string());
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error("demo: cannot create " + dir.string() + ": " + ec.message());
  const std::string exe = self_path();
  const auto& embedded = embedded::files();
  std::vector<std::pair<std::string, std::string>> written;  // h5, html
  int failures = 0;
  auto t0 = std::chrono::steady_clock::now();
  int k = 0;
  for (const DemoStep& s : kSteps) {
    ++k;
    if (!embedded.count(s.config)) throw Error(std::string("demo: embedded config missing: ") + s.config);
    fs::path h5 = dir / s.output;
    std::cerr << "\n[" << k << "/" << std::size(kSteps) << "] phasmid " << s.verb << " " << s.config << "\n    "
              << s.what << "\n";
    int rc = run_child({exe, s.verb, s.config, "-o", h5.string()});
    // fit exits 3 when it stops without convergence but has written its result.
    if (rc != 0 && !(rc == 3 && fs::exists(h5))) {
      std::cerr << "    step failed (exit " << rc << "); continuing with the next step\n";
      ++failures;
      continue;
    }
    fs::path html = h5;
    html.replace_extension(".html");
    if (run_child({exe, "report", h5.string(), "-o", html.string()}) != 0) {
      std::cerr << "    report failed for " << h5 << "\n";
      ++failures;
      continue;
    }
    written.emplace_back(h5.string(), html.string());
  }
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "\nphasmid demo finished in " << static_cast<int>(secs) << " s. Results:\n";
  for (auto& [h5, html] : written) std::cout << "  " << h5 << "\n  " << html << "\n";
  if (failures) {
    std::cout << failures << " step(s) failed; see the messages above.\n";
    return 1;
  }
  return 0;
}

const RegisterVerb reg{{"demo", "Run the main job on embedded defaults: simulate, fit, sensitivities, sweep, global sensitivities, reports",
                        [](CLI::App& sub) {
                          auto dir = std::make_shared<std::string>();
                          sub.add_option("-o,--output", *dir, "output directory (default demo_output)");
                          return std::function<int()>([dir] { return run_demo(*dir); });
                        }}};
}  // namespace
}  // namespace phasmid::app
