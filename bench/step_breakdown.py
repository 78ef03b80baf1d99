#!/usr/bin/env python3
"""Per-step cost breakdown from a `perf record` profile: self time of every symbol, summed
into the parts of an integrator step.

    perf record -F 5000 -o P.data build/bench/bench_walking 3000 joint auto spiking 1e-6
    perf report -i P.data --no-children --sort dso,symbol --stdio -g none | python3 bench/step_breakdown.py

Debian's SUNDIALS libraries are stripped of their static functions: unnamed addresses in
libsundials_* count as the integrator's own step logic.
"""
import re
import sys

# First matching pattern wins; symbols are matched as perf prints them.
CATEGORIES = [
    ("jacobian (AD)", r"Jet<|fill_jacobian|fill_sparse_jacobian|jac_dense_cb|jac_sparse_cb|part_jac|jac_band_cb"),
    ("right-hand side", r"eval_components|joint_acceleration|rhs_cb|part_rhs|rhs_trampoline|__ieee754_exp|^exp|exp@|__exp|_ZGV\w*_exp|exp_each|pow|sincos|sinh|cosh|tanh|__sin|__cos|log|NetworkModel|NetworkPart|Model::rhs|muscle|export_value|input_angles"),
    ("factorisation", r"dense_lu_setup|klu_factor|klu_refactor|KLU.*[Ff]actor|GETRF|dense_scale_add_identity|ScaleAddI|sparse_scale_add|MatCopy|MatZero|Setup_Dense|Setup_KLU|amd|colamd|btf"),
    ("linear solves", r"dense_lu_solve|klu_solve|klu_l?t?solve|GETRS|Solve_Dense|Solve_KLU|klu_"),
    ("root functions and event location", r"root_cb|part_roots|[Rr]check|Rcheck|RootFind|cvRoot|arkRoot|Rootfind"),
    ("interpolation (outputs, parts' polynomials)", r"GetDky|update_polynomial|write_states|Interp"),
    ("output recording", r"record|H5|hdf5|push_back|write_outputs|_M_realloc"),
    ("vector kernels (N_Vector)", r"linear_sum|wrms_norm|scale_add_multi|linear_combination|\bscale\b|::scale$|const_array|\binv\b|::inv$|prod|div|abs_value|add_const|max_norm|min_value|compare|inv_test|wsqr|dot|N_V|l1_norm|wl2"),
    ("Newton iteration", r"NonlinSol|Newton|cvNls|arkNls"),
    ("integrator core (CVODES/ARKODE step logic)", r"CVode|cvStep|cvNordsieck|cvAdjustOrder|cvComplete|cvSet|cvPredict|cvRescale|cvRestore|cvDo|cvHandle|cvLs|cvUpdate|cvIncreaseBDF|cvChooseEta|cvIncrease|cvDecrease|cv[A-Z]|ERKStep|erkStep|arkStep|arkEvolve|ark[A-Z]|ARKode|SUNAdapt|arkAdapt|ERK|SUNContext|SUNLinSol|SUNMat"),
    ("memory, libc", r"memmove|memcpy|memset|malloc|free|operator new|operator delete|_int_|cfree"),
    ("run loop and drivers", r"run_loop|run_partitioned|advance|Partitioned|take_roots|lagging|WholeSystem|handle_events|PartSolver|current_time|ProgressLine"),
    ("kernel, loader", r"\[k\]|do_lookup|_dl_|kallsyms"),
]


def main():
    totals = {name: 0.0 for name, _ in CATEGORIES}
    other, unknown = 0.0, {}
    for line in sys.stdin:
        m = re.match(r"\s*([\d.]+)%\s+(.*)$", line)
        if not m:
            continue
        pct, sym = float(m.group(1)), re.sub(r"[\s-]+$", "", m.group(2))
        if re.search(r"libsundials_\S+\s+\[\.\]\s+0x", sym):
            sym = "CVode (unnamed SUNDIALS function)"
        for name, pat in CATEGORIES:
            if re.search(pat, sym):
                totals[name] += pct
                break
        else:
            other += pct
            unknown[sym] = unknown.get(sym, 0) + pct
    for name, _ in CATEGORIES:
        if totals[name] >= 0.05:
            print(f"{totals[name]:6.1f} %  {name}")
    print(f"{other:6.1f} %  other")
    if "-v" in sys.argv:
        for sym, pct in sorted(unknown.items(), key=lambda kv: -kv[1])[:15]:
            print(f"        {pct:5.2f} %  {sym}", file=sys.stderr)


if __name__ == "__main__":
    main()
