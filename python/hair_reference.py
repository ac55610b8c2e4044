"""PBRT-v4's hair BSDF evaluated numerically: the reference for Rouge's fibre model.

Rouge's lashes and brows use `render/src/fibre.rs` (Marschner's R/TT/TRT lobes with Karis 2016's
closed-form fits). This script measures something nobody on the team wrote: PBRT-v4's `HairBxDF`
(Chiang, Bitterli, Tappan, Burley 2016; d'Eon, Francois, Hill, Letteri, Aubry 2011).

No pbrt code is in this file or in the repository. At run time the script reads a pbrt-v4 source
tree (`--pbrt-src`), extracts by text the pieces it needs -- the `HairBxDF` class from
`src/pbrt/bxdfs.h`, its constructor and `f()` from `src/pbrt/bxdfs.cpp`, and the small helpers
they call (`util/math.h`: Sqr, Pow, SafeSqrt, SafeASin, Radians, EvaluatePolynomial, FastExp,
Logistic, LogisticCDF, TrimmedLogistic, I0, LogI0; `util/float.h`: FloatToBits, BitsToFloat,
Exponent; `util/scattering.h`: FrDielectric; `util/vecmath.h`: AbsCosTheta) -- and fails naming
the file and the function when one is not found. It writes them into a temporary C++ file after
a shim of its own (scalar `Float`, a 3-component `Vector3f`, a one-channel `SampledSpectrum`,
empty stand-ins for the types the class only declares), compiles it with `g++ -O2` in a
temporary folder, runs it and writes the CSV. Only the numbers are committed.

    .venv/bin/python python/hair_reference.py --pbrt-src /tmp/pbrt-v4 \\
        --out data/hair/pbrt_v4_hair.csv [--pbrt-commit HASH]

(the commit is read with git when the tree is a checkout; otherwise pass it.)

Frames and directions
---------------------
pbrt's hair frame (its `BSDF` builds it with `Frame::FromXZ(dpdu, ns)`): x is the hair tangent
`dp/du` (the direction in which the curve is parametrised; root to tip for a curve written from
root to tip), z the shading normal, y = z × x. pbrt's `HairBxDF::f(wo, wi)` takes both directions
pointing away from the fibre (wo toward the eye, wi toward the light) and uses sin θ = w.x,
φ = atan2(w.z, w.y), and the azimuth difference φ_i − φ_o.

The CSV gives the directions in a fixed *fibre frame* (x = the tangent, z = toward the viewer
across the fibre, y = z × x), with θ the angle from the fibre's normal plane (sin θ = w·x) and
φ = φ_o − φ_i:

    wo = (sin θo, 0, cos θo)                 (φ_o = 90°, in pbrt's atan2(z, y))
    wi = (sin θi, cos θi sin φ, cos θi cos φ) (φ_i = 90° − φ)

so pbrt's φ_i − φ_o = −φ (the h-average is even in φ).

The quantity
------------
    f_avg(wi, wo) = (1/2) ∫_{−1}^{1} f_h(wo, wi) |cos θ_h(wi)| dh,

the average over the offset h across the fibre (uniform in h, as pbrt's camera rays hit a
fibre and as its furnace test samples it), where f_h is pbrt's
`HairBxDF(h, eta, sigma_a, beta_m, beta_n, alpha).f(wo, wi, Radiance)`. It is computed by the
midpoint rule in γ = asin h (pbrt's γ_o), N = 512 points:

    f_avg ≈ (π/2N) Σ_k f_{h_k} |cos θ_k| cos γ_k,   γ_k = (π/2)(−1 + (2k + 1)/N),  h_k = sin γ_k,

because the integrand has square-root edges at h = ±1 (TT of an absorbing fibre lives near the
rim): the plain midpoint rule in h with 256 points is off by up to 10 % there (σa = 4, φ = 180°),
the rule in γ with 512 points within 3e-4 of 8192 points on every row above 1e-4
(`--h-rule h` gives the plain rule).

cos θ_k(wi) = wi·n_k is the cosine against the shading normal n_k at offset h_k, as pbrt's
integrator multiplies it
(`bsdf.f(wo, wi) * AbsDot(wi, ns)`) and as pbrt's own white-furnace test does
(`hair.f(wo, wi) * AbsCosTheta(wi)` in src/pbrt/bsdfs_test.cpp, averaged over uniform h). n_k is
the normal of pbrt-v4's "cylinder" curve type: the viewer-facing z rotated about the tangent by
ψ = (π/2) h_k (the vector (x, y, z) of the fibre frame is (x, y cos ψ − z sin ψ, y sin ψ +
z cos ψ) in the local frame at h_k). pbrt's `f` divides by |cos θ(wi)| and this multiplies it
back, so f_avg does not depend on that choice: it is the h-average of pbrt's
Σ_p M_p A_p N_p. The per-h frame only keeps wi and wo off the local tangent plane (where pbrt's
f skips its division, or its `BSDF::f` returns 0 for wo.z = 0); the program counts such
evaluations and fails if any occurs.

Physically f_avg is the radiance a distant fibre sends toward wo per unit irradiance (on a plane
perpendicular to wi) of a directional light along wi: L = E · f_avg. PBRT's white-furnace
property is ∫_{S²} f_avg(wi, wo) dω_i = 1 for sigma_a = 0 (a fibre in a uniform environment of
radiance 1 has radiance 1); the header records it, the integral over wi on a midpoint grid in
(θi, φ) with dω = cos θ dθ dφ, and the integral over wo at fixed wi.

Parameters: eta = 1.55; alpha = 2 degrees (pbrt takes degrees); beta_n = 0.3; beta_m solved so
that pbrt's longitudinal standard deviation of the R lobe, sqrt(v[0]) with v[0] =
(a1 β + a2 β² + a3 β^n)² (coefficients read from the constructor's source: 0.726, 0.812, 3.7,
n = 20 in pbrt-v4), is 0.15 rad (bisection in binary64; the compiled program prints pbrt's own
sqrt(v[0]) back). pbrt then uses v[1] = v[0]/4 (TT) and v[2] = v[3] = 4 v[0] (TRT and beyond).
sigma_a is per unit radius (a path through the axis at normal incidence is 2 long), a scalar (one
channel of pbrt's SampledSpectrum).

pbrt-v4's scale tilt, as the code has it (`sinThetap_o` for p = 0, 1, 2): the R lobe peaks at
θo ≈ −θi + 2α, i.e. shifted toward +x (dp/du), TT at −θi − α and TRT at −θi − 4α (measured on
this output at θi = 0: R at +4.25°, TT at −1.75°). Marschner's R is shifted toward the root, so
with x from root to tip pbrt's signs are the reverse of the paper's (as noted in
tunabrain/tungsten issue #50); compare with a model whose tangent is −x to line the lobes up.

Run time: about 100 s on one core (the furnace integrals are most of it).

`Float` is `float`, as in pbrt's default build (`--double` compiles it as double, as
PBRT_FLOAT_AS_DOUBLE); the h-sums are accumulated in double.
"""

from __future__ import annotations

import argparse
import hashlib
import math
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ETA = 1.55
ALPHA_DEG = 2.0
BETA_N = 0.3
LONGITUDINAL_SD = 0.15
N_H = 512
SIGMA_A = (0.0, 0.25, 1.0, 4.0)
THETA_DEG = (-60, -30, 0, 30, 60)
PHI_DEG = tuple(range(0, 181, 15))
# Furnace grid: midpoints in θ over (−90°, 90°) and φ over (0°, 360°).
FURNACE_THETA = 90
FURNACE_PHI = 180


class ExtractionError(RuntimeError):
    pass


# ---------------------------------------------------------------------------------------------
# Text extraction (a small C++ scanner: comments, strings and characters are skipped when
# matching parentheses and braces).


def _skip_literal_or_comment(src: str, i: int) -> int:
    """If a comment or a string/char literal starts at i, the index after it; else i."""
    if src.startswith("//", i):
        j = src.find("\n", i)
        return len(src) if j < 0 else j
    if src.startswith("/*", i):
        j = src.find("*/", i + 2)
        return len(src) if j < 0 else j + 2
    if src[i] in "\"'":
        # Not a digit separator (C++14 1'000) -- pbrt does not use them in these files.
        q = src[i]
        j = i + 1
        while j < len(src) and src[j] != q:
            j += 2 if src[j] == "\\" else 1
        return j + 1
    return i


def _match(src: str, i: int, open_c: str, close_c: str) -> int:
    """src[i] == open_c; the index just past its matching close_c."""
    assert src[i] == open_c
    depth = 0
    while i < len(src):
        j = _skip_literal_or_comment(src, i)
        if j != i:
            i = j
            continue
        c = src[i]
        if c == open_c:
            depth += 1
        elif c == close_c:
            depth -= 1
            if depth == 0:
                return i + 1
        i += 1
    raise ExtractionError("unbalanced " + open_c + close_c)


def _line_start(src: str, i: int) -> int:
    return src.rfind("\n", 0, i) + 1


def _statement_start(src: str, i: int) -> int:
    """Start of the declaration whose name is at i: back over the lines before it that belong
    to it (template heads, PBRT_CPU_GPU, return types), stopping at a blank, comment or
    preprocessor line or one that ends a statement or block."""
    start = _line_start(src, i)
    while start > 0:
        prev_start = _line_start(src, start - 1)
        prev = src[prev_start : start - 1].strip()
        if not prev or prev.startswith(("//", "#", "/*", "*")) or prev.endswith((";", "}", "{", "*/", ":")):
            break
        start = prev_start
    return start


def _definitions(path: Path, name: str, reject: re.Pattern | None = None) -> list[str]:
    """Every function definition (with a body) named `name` in `path`, in file order; those
    whose signature matches `reject` are left out (overloads on types the shim lacks)."""
    src = path.read_text()
    out = []
    for m in re.finditer(r"\b" + re.escape(name) + r"\s*(?:<[^<>;(){}]*>)?\s*\(", src):
        # Only a declaration's name: the previous token must not be '.', '->' or '::'.
        before = src[: m.start()].rstrip()
        if before.endswith((".", "->", "::")):
            continue
        open_paren = m.end() - 1
        try:
            close = _match(src, open_paren, "(", ")")
        except ExtractionError:
            continue
        rest = re.match(r"\s*(?:const\s*|noexcept\s*|override\s*)*\{", src[close:])
        if not rest:
            continue
        start = _statement_start(src, m.start())
        head = src[start : m.start()]
        if re.search(r"\b(if|while|for|switch|return|else)\b|[=;]", head):
            continue  # a call inside a statement, not a definition
        body_open = close + rest.end() - 1
        end = _match(src, body_open, "{", "}")
        signature = src[start:close]
        if reject is not None and reject.search(signature):
            continue
        out.append(src[start:end])
    if not out:
        raise ExtractionError(f"{path}: no definition of function `{name}` found (has the layout changed?)")
    return out


def _class_definition(path: Path, name: str) -> str:
    src = path.read_text()
    m = re.search(r"^\s*class\s+" + re.escape(name) + r"\b[^;{]*\{", src, re.M)
    if not m:
        raise ExtractionError(f"{path}: no definition of class `{name}` found (has the layout changed?)")
    end = _match(src, m.end() - 1, "{", "}")
    if not src[end:].lstrip().startswith(";"):
        raise ExtractionError(f"{path}: class `{name}` does not end with '}};'")
    return src[m.start() : end].strip("\n") + ";"


def _member_definition(path: Path, qualified: str) -> str:
    """An out-of-class member definition such as `HairBxDF::f` (or the constructor
    `HairBxDF::HairBxDF`), with its initialiser list."""
    src = path.read_text()
    for m in re.finditer(r"\b" + re.escape(qualified) + r"\s*\(", src):
        close = _match(src, m.end() - 1, "(", ")")
        tail = re.match(r"\s*(?:const\s*)?(?::[^{;]*)?\{", src[close:])
        if not tail:
            continue
        end = _match(src, close + tail.end() - 1, "{", "}")
        return src[_statement_start(src, m.start()) : end]
    raise ExtractionError(f"{path}: no definition of `{qualified}` found (has the layout changed?)")


# Overloads of the helpers on types the shim does not provide.
_FOREIGN_TYPES = re.compile(r"\b(Interval|SampledSpectrum|Spectrum|complex|Vector3\w*|Point\w*|Normal\w*|Tuple\w*|long double)\b")


def extract(pbrt_src: Path) -> tuple[str, dict[str, str], list[float]]:
    """The pbrt pieces (C++ text), the sha256 of each file read, and the β_m → sqrt(v) polynomial
    coefficients (a1, a2, a3, n) read from the constructor."""
    root = pbrt_src / "src" / "pbrt"
    files = {
        "bxdfs.h": root / "bxdfs.h",
        "bxdfs.cpp": root / "bxdfs.cpp",
        "util/math.h": root / "util" / "math.h",
        "util/float.h": root / "util" / "float.h",
        "util/scattering.h": root / "util" / "scattering.h",
        "util/vecmath.h": root / "util" / "vecmath.h",
    }
    for key, p in files.items():
        if not p.is_file():
            raise ExtractionError(f"{p}: missing (is --pbrt-src a pbrt-v4 checkout?)")
    parts: list[str] = []

    def add(key: str, names: list[str], reject: re.Pattern | None = _FOREIGN_TYPES):
        for n in names:
            defs = _definitions(files[key], n, reject)
            parts.append(f"// ---- {key}: {n}\n" + "\n\n".join(defs))

    add("util/float.h", ["FloatToBits", "BitsToFloat", "Exponent"])
    add("util/math.h", ["Sqr", "Pow", "SafeSqrt", "SafeASin", "Radians", "EvaluatePolynomial", "FastExp",
                        "Logistic", "LogisticCDF", "TrimmedLogistic", "I0", "LogI0"])
    add("util/scattering.h", ["FrDielectric"])
    add("util/vecmath.h", ["AbsCosTheta"], None)
    parts.append("// ---- bxdfs.h: class HairBxDF\n" + _class_definition(files["bxdfs.h"], "HairBxDF"))
    ctor = _member_definition(files["bxdfs.cpp"], "HairBxDF::HairBxDF")
    parts.append("// ---- bxdfs.cpp: HairBxDF::HairBxDF\n" + ctor)
    parts.append("// ---- bxdfs.cpp: HairBxDF::f\n" + _member_definition(files["bxdfs.cpp"], "HairBxDF::f"))

    num = r"([0-9]*\.?[0-9]+)f?"
    m = re.search(r"v\[0\]\s*=\s*Sqr\(\s*" + num + r"\s*\*\s*beta_m\s*\+\s*" + num + r"\s*\*\s*Sqr\(beta_m\)\s*\+\s*"
                  + num + r"\s*\*\s*Pow<(\d+)>\(beta_m\)\s*\)", ctor)
    if not m:
        raise ExtractionError(f"{files['bxdfs.cpp']}: HairBxDF::HairBxDF: the beta_m -> v[0] mapping "
                              "`v[0] = Sqr(a*beta_m + b*Sqr(beta_m) + c*Pow<n>(beta_m))` was not found")
    coeffs = [float(m.group(1)), float(m.group(2)), float(m.group(3)), int(m.group(4))]
    sha = {k: hashlib.sha256(p.read_bytes()).hexdigest() for k, p in files.items()}
    return "\n\n".join(parts), sha, coeffs


# ---------------------------------------------------------------------------------------------
# The shim (this project's) and the driver program.

SHIM = r"""
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>

#define PBRT_CPU_GPU
#define DCHECK(x) ((void)0)
#define DCHECK_GE(a, b) ((void)0)
#define DCHECK_LT(a, b) ((void)0)
#define DCHECK_GT(a, b) ((void)0)
#define CHECK(x) do { if (!(x)) { std::fprintf(stderr, "CHECK failed: %s\n", #x); std::abort(); } } while (0)

#ifdef SHIM_DOUBLE
using Float = double;
#else
using Float = float;
#endif
constexpr Float Pi = 3.14159265358979323846;
constexpr Float Infinity = std::numeric_limits<Float>::infinity();

template <typename T, typename U, typename V> inline T Clamp(T v, U lo, V hi) {
    return v < T(lo) ? T(lo) : (v > T(hi) ? T(hi) : v);
}
inline float FMA(float a, float b, float c) { return std::fma(a, b, c); }
inline double FMA(double a, double b, double c) { return std::fma(a, b, c); }
inline bool IsInf(Float v) { return std::isinf(v); }
inline bool IsNaN(Float v) { return std::isnan(v); }

namespace pstd {
template <typename T, std::size_t N> using array = std::array<T, N>;
template <typename T> using optional = std::optional<T>;
inline float floor(float v) { return std::floor(v); }
inline double floor(double v) { return std::floor(v); }
template <typename To, typename From> inline To bit_cast(const From &f) {
    static_assert(sizeof(To) == sizeof(From));
    To t;
    std::memcpy(&t, &f, sizeof(To));
    return t;
}
}  // namespace pstd

struct Vector3f { Float x, y, z; };
struct Point2f { Float x, y; };

// One channel of pbrt's SampledSpectrum (sigma_a is a scalar here).
struct SampledSpectrum {
    Float c = 0;
    SampledSpectrum() = default;
    explicit SampledSpectrum(Float v) : c(v) {}
    explicit operator bool() const { return c != 0; }
    Float Average() const { return c; }
    SampledSpectrum &operator+=(const SampledSpectrum &o) { c += o.c; return *this; }
    SampledSpectrum &operator/=(Float v) { c /= v; return *this; }
};
inline SampledSpectrum operator+(SampledSpectrum a, SampledSpectrum b) { return SampledSpectrum(a.c + b.c); }
inline SampledSpectrum operator-(SampledSpectrum a) { return SampledSpectrum(-a.c); }
inline SampledSpectrum operator-(SampledSpectrum a, SampledSpectrum b) { return SampledSpectrum(a.c - b.c); }
inline SampledSpectrum operator-(Float a, SampledSpectrum b) { return SampledSpectrum(a - b.c); }
inline SampledSpectrum operator*(SampledSpectrum a, SampledSpectrum b) { return SampledSpectrum(a.c * b.c); }
inline SampledSpectrum operator*(SampledSpectrum a, Float b) { return SampledSpectrum(a.c * b); }
inline SampledSpectrum operator*(Float a, SampledSpectrum b) { return SampledSpectrum(a * b.c); }
inline SampledSpectrum operator/(SampledSpectrum a, SampledSpectrum b) { return SampledSpectrum(a.c / b.c); }
inline SampledSpectrum operator/(SampledSpectrum a, Float b) { return SampledSpectrum(a.c / b); }
inline SampledSpectrum Exp(SampledSpectrum a) { return SampledSpectrum(std::exp(a.c)); }

// Types the class only names in declarations it does not define here.
enum class TransportMode { Radiance, Importance };
enum class BxDFReflTransFlags { Unset = 0, Reflection = 1, Transmission = 2, All = 3 };
enum class BxDFFlags { Unset = 0, Reflection = 1, Transmission = 2, Diffuse = 4, Glossy = 8, Specular = 16,
                       GlossyReflection = 9 };
struct BSDFSample {};
struct SampledWavelengths {};
struct RGBUnboundedSpectrum {};

#define private public
"""

DRIVER = r"""
#undef private

// ---- this project's driver
struct Params { double eta, beta_m, beta_n, alpha_deg; int nh; bool gamma_rule; };
static long long g_on_plane = 0;

// f(wo, wi) |cos θ(wi)| averaged over h, (1/2) ∫ dh, by the midpoint rule in γ = asin h
// ((1/2) ∫ f(sin γ) cos γ dγ) or in h; wi, wo in the fibre frame.
static double f_avg(const Params &P, double sigma_a, const double wi[3], const double wo[3]) {
    const double pi = 3.14159265358979323846;
    double sum = 0;
    for (int k = 0; k < P.nh; ++k) {
        double u = -1 + (2.0 * k + 1) / P.nh, h = u, weight = 1;
        if (P.gamma_rule) {
            h = std::sin(0.5 * pi * u);
            weight = 0.5 * pi * std::cos(0.5 * pi * u);
        }
        double psi = 0.5 * pi * h, c = std::cos(psi), s = std::sin(psi);
        Vector3f wil{Float(wi[0]), Float(wi[1] * c - wi[2] * s), Float(wi[1] * s + wi[2] * c)};
        Vector3f wol{Float(wo[0]), Float(wo[1] * c - wo[2] * s), Float(wo[1] * s + wo[2] * c)};
        if (wol.z <= 0 || wil.z == 0) ++g_on_plane;  // where pbrt would not divide, or BSDF::f return 0
        HairBxDF hair(Float(h), Float(P.eta), SampledSpectrum(Float(sigma_a)), Float(P.beta_m), Float(P.beta_n),
                      Float(P.alpha_deg));
        sum += weight * double(hair.f(wol, wil, TransportMode::Radiance).Average()) * double(AbsCosTheta(wil));
    }
    return sum / P.nh;
}

static void dir(double theta, double phi_from_z, double out[3]) {
    out[0] = std::sin(theta);
    out[1] = std::cos(theta) * std::sin(phi_from_z);
    out[2] = std::cos(theta) * std::cos(phi_from_z);
}

int main(int argc, char **argv) {
    if (argc < 8) { std::fprintf(stderr, "usage: prog eta beta_m beta_n alpha_deg nh gamma|h mode ...\n"); return 2; }
    Params P{std::atof(argv[1]), std::atof(argv[2]), std::atof(argv[3]), std::atof(argv[4]), std::atoi(argv[5]),
             std::string(argv[6]) == "gamma"};
    std::string mode = argv[7];
    argv += 1;  // the mode's own arguments start at argv[7]
    const double pi = 3.14159265358979323846;
    if (mode == "info") {
        HairBxDF hair(Float(0), Float(P.eta), SampledSpectrum(Float(0)), Float(P.beta_m), Float(P.beta_n),
                      Float(P.alpha_deg));
        std::printf("%.9g %.9g %.9g %.9g %.9g\n", std::sqrt(double(hair.v[0])), std::sqrt(double(hair.v[1])),
                    std::sqrt(double(hair.v[2])), std::sqrt(double(hair.v[3])), double(hair.s));
        return 0;
    }
    if (mode == "eval") {
        // stdin: sigma_a wi_x wi_y wi_z wo_x wo_y wo_z per line; stdout: f_avg.
        double sa, wi[3], wo[3];
        while (std::scanf("%lf %lf %lf %lf %lf %lf %lf", &sa, &wi[0], &wi[1], &wi[2], &wo[0], &wo[1], &wo[2]) == 7)
            std::printf("%.9g\n", f_avg(P, sa, wi, wo));
        std::fprintf(stderr, "on_plane %lld\n", g_on_plane);
        return g_on_plane ? 3 : 0;
    }
    if (mode == "furnace") {
        // argv: sigma_a, 'i' (integrate over wi at fixed wo, theta = theta_o) or 'o' (over wo at
        // fixed wi), theta_deg, n_theta, n_phi. Midpoint grid, dω = cos θ dθ dφ.
        double sa = std::atof(argv[7]);
        bool over_wi = argv[8][0] == 'i';
        double th = std::atof(argv[9]) * pi / 180;
        int nt = std::atoi(argv[10]), np = std::atoi(argv[11]);
        // f_avg depends on the azimuths only through phi = phi_o - phi_i, so the azimuth of
        // the moving direction is taken as that difference, with wo kept in the x-z plane.
        double wi[3], wo[3];
        double sum = 0;
        for (int i = 0; i < nt; ++i) {
            double t = -pi / 2 + (i + 0.5) * pi / nt;
            for (int j = 0; j < np; ++j) {
                double p = (j + 0.5) * 2 * pi / np;
                dir(over_wi ? t : th, p, wi);
                dir(over_wi ? th : t, 0, wo);
                sum += f_avg(P, sa, wi, wo) * std::cos(t);
            }
        }
        std::printf("%.9g\n", sum * (pi / nt) * (2 * pi / np));
        std::fprintf(stderr, "on_plane %lld\n", g_on_plane);
        return g_on_plane ? 3 : 0;
    }
    std::fprintf(stderr, "unknown mode %s\n", mode.c_str());
    return 2;
}
"""


def build(pbrt_text: str, workdir: Path, double: bool) -> Path:
    src = workdir / "hair_reference.cpp"
    src.write_text(SHIM + "\n" + pbrt_text + "\n" + DRIVER)
    exe = workdir / "hair_reference"
    cmd = ["g++", "-std=c++17", "-O2", "-o", str(exe), str(src)]
    if double:
        cmd.insert(1, "-DSHIM_DOUBLE")
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"g++ failed on the extracted pbrt code ({src}):\n{r.stderr[-6000:]}")
    return exe


def solve_beta_m(a1: float, a2: float, a3: float, n: int, sd: float) -> float:
    g = lambda b: a1 * b + a2 * b * b + a3 * b**n - sd  # noqa: E731
    lo, hi = 0.0, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if g(mid) < 0 else (lo, mid)
    return 0.5 * (lo + hi)


def direction(theta_deg: float, phi_from_z_deg: float) -> tuple[float, float, float]:
    t, p = math.radians(theta_deg), math.radians(phi_from_z_deg)
    return (math.sin(t), math.cos(t) * math.sin(p), math.cos(t) * math.cos(p))


def pbrt_commit(src: Path, given: str | None) -> str:
    if given:
        return given
    try:
        top = subprocess.run(["git", "-C", str(src), "rev-parse", "--show-toplevel"], capture_output=True, text=True,
                             check=True).stdout.strip()
        if Path(top).resolve() != src.resolve():
            raise SystemExit(f"{src} is inside the git tree {top}, not a pbrt-v4 checkout: pass --pbrt-commit HASH")
        r = subprocess.run(["git", "-C", str(src), "rev-parse", "HEAD"], capture_output=True, text=True, check=True)
        return r.stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        raise SystemExit(f"{src} is not a git checkout: pass --pbrt-commit HASH")


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--pbrt-src", type=Path, required=True, help="a pbrt-v4 source tree")
    ap.add_argument("--out", type=Path, required=True, help="the CSV to write")
    ap.add_argument("--pbrt-commit", help="the tree's commit when it is not a git checkout")
    ap.add_argument("--nh", type=int, default=N_H, help="midpoint samples over the offset (default 512)")
    ap.add_argument("--h-rule", choices=("gamma", "h"), default="gamma",
                    help="midpoint rule in gamma = asin(h) (default) or in h itself")
    ap.add_argument("--double", action="store_true", help="compile pbrt's Float as double")
    ap.add_argument("--keep", action="store_true", help="keep the temporary C++ folder")
    args = ap.parse_args(argv)

    commit = pbrt_commit(args.pbrt_src, args.pbrt_commit)
    try:
        text, sha, (a1, a2, a3, n) = extract(args.pbrt_src)
    except ExtractionError as e:
        raise SystemExit(f"extraction failed: {e}")
    beta_m = solve_beta_m(a1, a2, a3, n, LONGITUDINAL_SD)
    print(f"beta_m = {beta_m!r} (sqrt(v0) = {a1}*b + {a2}*b^2 + {a3}*b^{n} = {LONGITUDINAL_SD})")

    workdir = Path(tempfile.mkdtemp(prefix="hair_reference_"))
    try:
        exe = build(text, workdir, args.double)
        base = [str(exe), repr(ETA), repr(beta_m), repr(BETA_N), repr(ALPHA_DEG), str(args.nh), args.h_rule]

        def run(extra: list[str], stdin: str | None = None) -> str:
            r = subprocess.run(base + extra, input=stdin, capture_output=True, text=True)
            if r.returncode != 0:
                raise SystemExit(f"{' '.join(base + extra)} failed ({r.returncode}): {r.stderr}")
            return r.stdout

        sd = [float(x) for x in run(["info"]).split()]
        print(f"pbrt's longitudinal sd sqrt(v[0..3]) = {sd[:4]}, azimuthal logistic s = {sd[4]}")
        if abs(sd[0] - LONGITUDINAL_SD) > 1e-5:
            raise SystemExit(f"pbrt's sqrt(v[0]) = {sd[0]}, not {LONGITUDINAL_SD}")

        rows, lines = [], []
        for sa in SIGMA_A:
            for ti in THETA_DEG:
                for to in THETA_DEG:
                    for ph in PHI_DEG:
                        wi, wo = direction(ti, ph), direction(to, 0.0)
                        rows.append((sa, ti, to, ph, wi, wo))
                        lines.append(" ".join(repr(v) for v in (sa, *wi, *wo)))
        vals = run(["eval"], "\n".join(lines) + "\n").split()
        assert len(vals) == len(rows)

        furnace = []  # (sigma_a, over, theta, value)
        for sa in SIGMA_A:
            for over in "io":
                for th in THETA_DEG:
                    v = float(run(["furnace", repr(sa), over, str(th), str(FURNACE_THETA), str(FURNACE_PHI)]))
                    furnace.append((sa, over, th, v))
                    print(f"sigma_a {sa}: integral over w{over} at theta_{'o' if over == 'i' else 'i'} = {th:>3} deg: {v:.6f}")

        flt = "double" if args.double else "float"
        head = [
            "# PBRT-v4 HairBxDF (Chiang, Bitterli, Tappan, Burley 2016; d'Eon, Francois, Hill, Letteri, Aubry 2011),",
            "# evaluated numerically by python/hair_reference.py from the pbrt-v4 source at run time;",
            f"# pbrt-v4 commit {commit} (github.com/mmp/pbrt-v4, Apache-2.0); only these numbers are committed.",
            "# sha256 of the files read: " + ", ".join(f"{k} {v[:16]}" for k, v in sha.items()),
            f"# Parameters: eta {ETA}, alpha {ALPHA_DEG} degrees, beta_n {BETA_N}, beta_m {beta_m:.9f}",
            f"#   (pbrt's sqrt(v) of the R lobe = {sd[0]:.6f} rad; TT {sd[1]:.6f}, TRT {sd[2]:.6f}; logistic s {sd[4]:.6f}),",
            f"#   sigma_a per unit fibre radius (scalar), Float = {flt}.",
            "# Quantity: f_avg = (1/2) int_{-1}^{1} HairBxDF(h).f(wo, wi, Radiance) * |wi . n_h| dh, the average over",
            "#   the offset h across the fibre, n_h the shading normal at h (pbrt's f divides by that cosine; this is",
            "#   the quantity pbrt's white-furnace test integrates to 1); "
            + (f"midpoint rule in gamma = asin(h), {args.nh} points." if args.h_rule == "gamma"
               else f"midpoint rule in h, {args.nh} points."),
            "#   L = E * f_avg for a directional light of irradiance E (perpendicular to wi). Units 1/sr.",
            "# Frame (columns wi_*, wo_*): x = the hair tangent (pbrt's dp/du), z toward the viewer across the fibre,",
            "#   y = z cross x; wi toward the light, wo toward the eye, both away from the fibre; sin(theta) = w.x;",
            "#   wo = (sin to, 0, cos to), wi = (sin ti, cos ti sin phi, cos ti cos phi): phi = phi_o - phi_i,",
            "#   phi measured with pbrt's atan2(w.z, w.y) (pbrt's own phi_i - phi_o is -phi; f_avg is even in phi).",
            "#   pbrt-v4's scale tilt puts R at theta_o ~ -theta_i + 2 alpha (toward +x), TT at -theta_i - alpha,",
            "#   TRT at -theta_i - 4 alpha: the reverse of Marschner's signs if x runs root to tip.",
            f"# Furnace, midpoint grid {FURNACE_THETA} x {FURNACE_PHI} in (theta, phi), d omega = cos(theta) dtheta dphi:",
        ]
        for sa in SIGMA_A:
            for over, label in (("i", "int f_avg d omega_i at theta_o"), ("o", "int f_avg d omega_o at theta_i")):
                vals_f = [f"{th}: {v:.5f}" for (s2, o2, th, v) in furnace if s2 == sa and o2 == over]
                head.append(f"#   sigma_a {sa}: {label} = " + ", ".join(vals_f))
        out_lines = head + ["sigma_a,theta_i_deg,theta_o_deg,phi_deg,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,f_avg"]
        for (sa, ti, to, ph, wi, wo), v in zip(rows, vals):
            vec = ",".join(f"{c:.9f}" for c in (*wi, *wo)).replace("-0.000000000", "0.000000000")
            out_lines.append(f"{sa},{ti},{to},{ph},{vec},{float(v):.7g}")
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text("\n".join(out_lines) + "\n")
        print(f"wrote {args.out} ({len(rows)} rows)")
    finally:
        if args.keep:
            print(f"kept {workdir}")
        else:
            shutil.rmtree(workdir, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
