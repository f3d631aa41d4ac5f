// Names shared by the scene description and the contact solver.
#pragma once

namespace splat {

// How contact forces are computed: Lagrange multipliers (thesis 1.3.3.3) or a
// penalty spring per penetrating pair (for comparison).
enum class ContactMethod { lagrange, penalty };

// How the Lagrange-multiplier system is solved: projected Gauss-Seidel (with
// friction) or a primal active set with sparse LDL^T solves (frictionless).
enum class ContactSolverKind { pgs, active_set };

}  // namespace splat
