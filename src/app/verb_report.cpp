// phasmid report RUN.h5 [-o REPORT.html]: one self-contained HTML page for any phasmid HDF5 file.
#include <iostream>

#include "app/verb.hpp"
#include "report/report.hpp"

namespace {
phasmid::app::RegisterVerb reg{{"report",
                                "Write a self-contained HTML report (figures and tables) of a phasmid HDF5 file",
                                [](CLI::App& sub) {
                                  auto input = std::make_shared<std::string>();
                                  auto output = std::make_shared<std::string>();
                                  sub.add_option("RUN.h5", *input, "phasmid HDF5 file")->required();
                                  sub.add_option("-o,--output", *output,
                                                 "HTML file to write (default: RUN.html next to the input)");
                                  return std::function<int()>([input, output] {
                                    std::string out = output->empty()
                                                          ? phasmid::report::default_output_path(*input)
                                                          : *output;
                                    phasmid::report::write_report(*input, out);
                                    std::cout << out << "\n";
                                    return 0;
                                  });
                                }}};
}  // namespace
