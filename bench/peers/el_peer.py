#!/usr/bin/env python3
"""The plain Euler–Lagrange derivation of a serial robot, for symdyn's benchmark peers.

One derivation, written once, run with SymPy or with SymEngine (the `symengine` package, a C++
computer-algebra system), on a robot description that `symdyn bench` writes as JSON (see
`src/bench/peer.rs` for the format): the DH transforms, the centre-of-mass Jacobians J_v,i (by
differentiation) and J_w,i (from the joint axes), the inertia matrix

    D(q) = sum_i m_i J_v,i^T J_v,i + J_w,i^T R_i I_i R_i^T J_w,i,

the Christoffel symbols c_ijk = 1/2 (dd_kj/dq_i + dd_ki/dq_j - dd_ij/dq_k) for i <= j (c_ijk = c_jik),
the potential P = -sum_i m_i g0 . p_ci and g_k = dP/dq_k (Spong, Hutchinson and Vidyasagar, ch. 7).
This is what a user writes first: no simplification, except `--trigsimp`, which applies SymPy's
`trigsimp` to every entry of D(q) (SymEngine has no trigsimp).

It prints one JSON line:
  {"engine": ..., "trigsimp": ..., "status": "ok", "seconds": ..., "ops": ..., "terms": ...}
where `seconds` is the derivation alone (after the interpreter has started and the engine is
imported), `ops` the additions and multiplications of D, the Christoffel symbols and g counted on the
expression trees as symdyn counts them (a sum of k terms: k-1 additions; a product of k factors: k-1
multiplications; an integer power x^n: n-1 multiplications; a rational coefficient: one
multiplication; functions and other powers: one operation each), and `terms` the number of additive
terms of all those entries. The caller enforces the time limit by killing the process.
"""

import argparse
import json
import sys
import time


def load_engine(name):
    if name == "sympy":
        import sympy as E
    elif name == "symengine":
        import symengine as E
    else:
        raise SystemExit(f"unknown engine {name!r}: sympy or symengine")
    return E


def parser(E, robot):
    """A function from symdyn's ASCII syntax to the engine's expressions. Every name in the robot's
    `symbols` list (and q1..qn) is declared a symbol first, so that names such as `I` or `E` are not
    read as the imaginary unit or Euler's number; SymPy parses (`^` is a power), and SymEngine
    converts SymPy's result."""
    import sympy
    names = list(robot.get("symbols", [])) + [f"q{i}" for i in range(1, robot["dof"] + 1)]
    local = {name: sympy.Symbol(name) for name in names}

    def parse(text):
        e = sympy.parse_expr(text.replace("^", "**"), local_dict=local)
        return e if E is sympy else E.sympify(e)

    return parse


def derive(E, robot, trigsimp, S):
    """Returns the list of result expressions: D (n*n), Christoffel symbols (i<=j, all k), g (n).
    `S` parses an expression of the robot description (see `parser`)."""
    n = robot["dof"]
    q = [E.Symbol(f"q{i}") for i in range(1, n + 1)]
    modified = robot.get("convention", "standard") == "modified"

    def rot_z(t):
        return E.Matrix([[E.cos(t), -E.sin(t), 0, 0], [E.sin(t), E.cos(t), 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])

    def rot_x(t):
        return E.Matrix([[1, 0, 0, 0], [0, E.cos(t), -E.sin(t), 0], [0, E.sin(t), E.cos(t), 0], [0, 0, 0, 1]])

    def trans(x, y, z):
        return E.Matrix([[1, 0, 0, x], [0, 1, 0, y], [0, 0, 1, z], [0, 0, 0, 1]])

    # T[i] = T_0^i, i = 0..n
    T = [E.eye(4)]
    for j in robot["joints"]:
        a, alpha, d, theta = (S(j[k]) for k in ("a", "alpha", "d", "theta"))
        if modified:
            A = rot_x(alpha) * trans(a, 0, 0) * rot_z(theta) * trans(0, 0, d)
        else:
            A = rot_z(theta) * trans(0, 0, d) * trans(a, 0, 0) * rot_x(alpha)
        T.append(T[-1] * A)

    def rot(M):
        return M[:3, :3]

    # Joint i's axis: z_{i-1} (standard) or z_i (modified).
    axes = []
    for i in range(1, n + 1):
        M = T[i] if modified else T[i - 1]
        axes.append(E.Matrix([M[0, 2], M[1, 2], M[2, 2]]))

    g0 = E.Matrix([S(x) for x in robot["gravity"]])
    D = E.zeros(n, n)
    P = E.Integer(0)
    for i, link in enumerate(robot["links"], start=1):
        m = S(link["mass"])
        r = E.Matrix([S(x) for x in link["com"]] + [1])
        p = (T[i] * r)[:3, 0]
        Jv = p.jacobian(E.Matrix(q))
        Jw = E.zeros(3, n)
        for k in range(i):
            if robot["joints"][k]["kind"] == "revolute":
                for row in range(3):
                    Jw[row, k] = axes[k][row]
        I = E.Matrix([[S(x) for x in row] for row in link["inertia"]])
        R = rot(T[i])
        D += m * Jv.T * Jv + Jw.T * (R * I * R.T) * Jw
        P -= m * (g0.T * p)[0, 0]

    if trigsimp:
        D = D.applyfunc(E.trigsimp)

    results = [D[k, j] for k in range(n) for j in range(n)]
    dD = [[[E.diff(D[k, j], q[i]) for i in range(n)] for j in range(n)] for k in range(n)]
    half = E.Rational(1, 2)
    for k in range(n):
        for i in range(n):
            for j in range(i, n):
                results.append(half * (dD[k][j][i] + dD[k][i][j] - dD[i][j][k]))
    for k in range(n):
        results.append(E.diff(P, q[k]))
    return results


def count(E, exprs):
    """(ops, terms) of `exprs`, counted on the trees with a cache per distinct node."""
    cache = {}

    def ops(e):
        key = e
        hit = cache.get(key)
        if hit is not None:
            return hit
        args = e.args
        if not args:
            c = 0
        elif e.is_Add:
            c = len(args) - 1 + sum(ops(a) for a in args)
        elif e.is_Mul:
            c = len(args) - 1 + sum(ops(a) for a in args)
        elif e.is_Pow:
            base, ex = args
            if ex.is_Integer and int(ex) > 0:
                c = int(ex) - 1 + ops(base)
            else:
                c = 1 + ops(base) + ops(ex)
        else:
            c = 1 + sum(ops(a) for a in args)
        cache[key] = c
        return c

    total = 0
    terms = 0
    for e in exprs:
        total += ops(e)
        terms += len(e.args) if e.is_Add else (0 if e == 0 else 1)
    return total, terms


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--engine", required=True, choices=["sympy", "symengine"])
    ap.add_argument("--trigsimp", action="store_true", help="trigsimp every entry of D (SymPy only)")
    ap.add_argument("--no-count", action="store_true", help="skip counting operations")
    ap.add_argument("--evaluate", metavar="VALUES.json",
                    help="also print D and g evaluated at these values ({\"q1\": 0.1, \"m1\": 2, ...}), "
                         "so that a test can compare the peer's numbers with symdyn's")
    ap.add_argument("robot", help="the robot description written by `symdyn bench`")
    args = ap.parse_args()
    if args.trigsimp and args.engine != "sympy":
        raise SystemExit("--trigsimp needs --engine sympy (SymEngine has no trigsimp)")
    with open(args.robot) as f:
        robot = json.load(f)
    E = load_engine(args.engine)
    version = getattr(E, "__version__", "?")
    # Parse the description's strings before the clock starts: the derivation alone is timed.
    parse = parser(E, robot)
    cache = {}

    def S(text):
        if text not in cache:
            cache[text] = parse(text)
        return cache[text]

    for j in robot["joints"]:
        for k in ("a", "alpha", "d", "theta"):
            S(j[k])
    for link in robot["links"]:
        S(link["mass"])
        for x in link["com"]:
            S(x)
        for row in link["inertia"]:
            for x in row:
                S(x)
    for x in robot["gravity"]:
        S(x)
    start = time.perf_counter()
    results = derive(E, robot, args.trigsimp, S)
    seconds = time.perf_counter() - start
    ops, terms = (None, None) if args.no_count else count(E, results)
    record = {
        "engine": args.engine,
        "version": version,
        "trigsimp": args.trigsimp,
        "status": "ok",
        "seconds": seconds,
        "ops": ops,
        "terms": terms,
    }
    if args.evaluate:
        with open(args.evaluate) as f:
            values = json.load(f)
        subs = {E.Symbol(k): E.Float(float(v)) for k, v in values.items()}
        n = robot["dof"]
        record["D"] = [float(e.subs(subs)) for e in results[: n * n]]
        record["g"] = [float(e.subs(subs)) for e in results[len(results) - n:]]
    print(json.dumps(record))


if __name__ == "__main__":
    sys.exit(main())
