"""The GIL is released while C++ integrates, and Ctrl-C interrupts a run (docs/python.md).
Nothing here assumes how fast a run goes: the interrupted runs are as long as a run may be
(1e7 ms of model time, the bound of docs/config.md "Limits": of the order of 100 s of computing
for a single joint, while the signal comes milliseconds after the start) and are interrupted once there is a sign that they are inside
C++ (phasmid's SIGINT handler installed, conftest.sigint_c_handler)."""
import faulthandler
import os
import signal
import time
from concurrent.futures import ThreadPoolExecutor

import pytest

import phasmid
from conftest import HANG_SECONDS, Child, assert_same_bits, config, sigint_c_handler

T_END_MS = 9000  # ~1 s of a single joint (the serial-bits check only)
OPEN_ENDED = dict(t_end_ms=1e7, output_dt_ms=1000)  # ended by the interrupt


def one(scenario):
    return scenario.simulate(t_end_ms=T_END_MS)


def test_python_threads_run_while_cpp_integrates():
    # The worker's run is guarded (phasmid's C SIGINT handler in place of Python's) from before
    # it releases the GIL until after it takes the GIL back. So this thread can see the guard
    # installed, and run Python while it is, only if the GIL is released during the run; with
    # the GIL held it would stand still until faulthandler's hang guard (a C thread) ends the
    # process with the tracebacks.
    s = phasmid.load(config("single_joint_fti.toml"))
    python_handler = sigint_c_handler()
    faulthandler.dump_traceback_later(HANG_SECONDS, exit=True)
    try:
        with ThreadPoolExecutor(1) as pool:
            future = pool.submit(s.simulate, **OPEN_ENDED)
            try:
                deadline = time.monotonic() + HANG_SECONDS
                while sigint_c_handler() == python_handler:
                    assert not future.done(), "the run ended without being inside C++: %r" % future.exception()
                    assert time.monotonic() < deadline, "hung: no guarded run within %d s" % HANG_SECONDS
                ticks = 0
                while ticks < 1000:  # Python runs while the worker is inside C++
                    assert sigint_c_handler() != python_handler and not future.done(), future.exception()
                    ticks += 1
                os.kill(os.getpid(), signal.SIGINT)  # phasmid's handler: asks the run to stop
                with pytest.raises(KeyboardInterrupt, match="interrupted at t = "):
                    future.result(timeout=HANG_SECONDS)
            finally:
                # On a failed check the open-ended run must still be ended before the pool waits for it.
                deadline = time.monotonic() + HANG_SECONDS
                while not future.done() and sigint_c_handler() != python_handler and time.monotonic() < deadline:
                    os.kill(os.getpid(), signal.SIGINT)
                    time.sleep(0.01)
        assert sigint_c_handler() == python_handler, "Python's SIGINT handler not restored after the run"
    finally:
        faulthandler.cancel_dump_traceback_later()


def test_two_threads_at_once_give_the_serial_bits():
    # One scenario run by two threads at once: a run never changes its scenario, so both give
    # the serial run's numbers to the last bit. (How much faster two threads are is the
    # machine's free cores as much as phasmid: bench/bench_python.py prints it.)
    s = phasmid.load(config("single_joint_fti.toml"))
    serial = one(s)
    with ThreadPoolExecutor(2) as pool:
        runs = list(pool.map(one, [s, s]))
    assert_same_bits(serial.y, runs[0].y)
    assert_same_bits(serial.y, runs[1].y)


INTERRUPTED = r"""
import sys, phasmid
from conftest import print_running_when_guarded
s = phasmid.load(sys.argv[1])
print_running_when_guarded()
try:
    s.simulate(t_end_ms=1e7, output_dt_ms=1000)  # the longest run allowed: the interrupt ends it
except KeyboardInterrupt as e:
    print("interrupted: %s" % e, flush=True)
    s.simulate(t_end_ms=100, discard_ms=0)  # the next run is not affected
    print("next run ok", flush=True)
"""


def test_ctrl_c_interrupts_a_long_run():
    child = Child(INTERRUPTED, config("single_joint_fti.toml"))
    child.wait_for_line("running")  # the run is inside C++, its SIGINT handler installed
    child.p.send_signal(signal.SIGINT)
    rc, out, err = child.finish()
    assert rc == 0, err
    assert "interrupted: " in out and "interrupted at t = " in out and "next run ok" in out, out + err
