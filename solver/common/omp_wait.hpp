// The OpenMP wait policy of the process. GNU libgomp reads OMP_WAIT_POLICY
// once, when it is loaded (before main), so a setenv in main reaches only
// child processes: the process itself must be started again with it set.
//
// Without a setting libgomp lets a thread that finished its share of a
// parallel region spin for a while before it sleeps. A step opens many
// regions, so on a shared machine (campaign jobs, Slurm nodes, a laptop)
// the spinning thread burns the time slice its partner needs: two threads
// ran 4-10x slower than one on a loaded 2-core machine (issue 28).
#pragma once

#include <string>

namespace splat {

// Where OMP_WAIT_POLICY is not set, sets it to passive and replaces the
// process by a fresh start of the same executable with the same arguments
// (/proc/self/exe); returns only where it was set already or the restart
// failed (the process then runs with libgomp's default).
void restart_with_passive_omp_wait(char** argv);

// OMP_WAIT_POLICY as the process was started with it (what libgomp read):
// "passive", "active", or "" when unset.
std::string omp_wait_policy_at_start();

}  // namespace splat
