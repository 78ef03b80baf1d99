#pragma once
// The scales of estimated parameters (PEtab's parameterScale): optimisers and samplers move
// x = scale(theta); Jacobians carry the chain rule d theta / d x. Defined in parameter_table.cpp.
#include <string>

namespace phasmid::fit {

enum class Scale { Lin, Log, Log10 };
Scale parse_scale(const std::string& s);  // "lin" | "log" | "log10"; throws Error otherwise
const char* scale_name(Scale s);

// theta <-> x and d theta / d x.
double to_scaled(Scale s, double theta);
double from_scaled(Scale s, double x);
double dtheta_dx(Scale s, double x);

}  // namespace phasmid::fit
