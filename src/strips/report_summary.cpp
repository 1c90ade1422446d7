// Readable summary of a strip adjustment (report_output.h).
#include <pcl_ls3d/strips/report_output.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>

namespace pcl_ls3d {
namespace strips {

namespace {

void
add(std::string& out, const char* fmt, ...) __attribute__((format(printf, 2, 3)));

void
add(std::string& out, const char* fmt, ...)
{
  char buf[1024];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buf, sizeof(buf), fmt, args);
  va_end(args);
  out += buf;
}

// "value ± σ" with σ "fixed" / "undet." where there is none.
std::string
withSigma(double v, double s, double factor, const char* fmt)
{
  char a[48], b[48];
  std::snprintf(a, sizeof(a), fmt, v * factor);
  if (s == 0.0)
    std::snprintf(b, sizeof(b), "%-9s", "fixed");
  else if (!std::isfinite(s))
    std::snprintf(b, sizeof(b), "%-9s", "undet.");
  else
    std::snprintf(b, sizeof(b), "\u00b1%-8.4f", s * factor);
  return std::string(a) + " " + b;
}

// The held-out scale per strip (model_adequacy.h), or why it was not tested.
std::string
heldOutSummary(const StripAdjustmentReport& r, const std::string& u)
{
  std::string out;
  const HeldOutTest& t = r.held_out;
  if (!t.tested) {
    if (!t.note.empty())
      add(out, "\nheld-out parameters: not tested (%s)\n", t.note.c_str());
    return out;
  }
  add(out,
      "\nheld-out scale if freed (%s): chi2 %.1f with %d dof; significant on %d strips, larger than the own "
      "noise on %d\n",
      t.note.c_str(), t.statistic, t.dof, t.significant, t.flagged);
  add(out, "strip          m-1 [ppm]   sigma [ppm]   z       edge effect [%s]   own noise [%s]\n", u.c_str(),
      u.c_str());
  for (const StripResult& s : r.strips)
    for (const HeldOutParameter& h : s.held_out)
      add(out, "%-12s %+10.2f   %9.2f   %+7.2f   %12.4f   %14.4f   %s\n", s.name.c_str(), 1e6 * h.estimate,
          1e6 * h.sigma, h.z, h.effect, h.noise,
          h.flagged       ? "FREE THE SCALE (-params 7)"
          : h.significant ? "significant, within the noise"
                          : "");
  return out;
}

}  // namespace

std::string
reportSummary(const StripAdjustmentReport& r, const std::string& u)
{
  std::string out;
  add(out,
      "%s after %d iterations: sigma0 %.4f %s, %zu observations, redundancy %ld, %d unknowns (%s, rule %s, "
      "%s)\n",
      terminationTypeToString(r.termination), r.iterations, r.sigma0, u.c_str(), r.observations, r.redundancy,
      r.unknowns, r.model == "z" ? "height only" : (r.model + " parameters").c_str(), r.rule.c_str(),
      r.estimator.c_str());
  if (!r.message.empty())
    add(out, "  %s\n", r.message.c_str());
  for (const std::string& n : r.notes)
    add(out, "  note: %s\n", n.c_str());
  add(out, "  sigmas: %s\n\n", r.precision_model.c_str());
  // Each parameter's column is 20 characters wide, whatever the length unit's name.
  out += "strip          points   ";
  for (const std::string& column :
       {"tx [" + u + "]", "ty [" + u + "]", "tz [" + u + "]", std::string("phi [mrad]"),
        std::string("omega [mrad]"), std::string("kappa [mrad]")})
    add(out, "%-20s", column.c_str());
  out += "m-1 [ppm]\n";
  for (const StripResult& s : r.strips) {
    add(out, "%-12s %8zu", s.name.c_str(), s.points);
    for (int q = 0; q < 7; ++q) {
      const double factor = q < 3 ? 1.0 : q < 6 ? 1e3 : 1e6;
      const double value = q == 6 ? s.parameters[q] - 1.0 : s.parameters[q];
      out += "  " + withSigma(value, s.sigmas[q], factor, q < 3 ? "%+8.4f" : "%+8.4f");
    }
    add(out, "  %s\n", s.note.c_str());
  }
  out += heldOutSummary(r, u);
  add(out,
      "\noverlap                 area [%s2]   obs used/rejected   sigma0    before: RMS  sigmaMAD  ->  "
      "after: RMS  sigmaMAD   own noise sigmaMAD i / j\n",
      u.c_str());
  for (const OverlapResult& o : r.overlaps) {
    const std::string name =
        r.strips[static_cast<std::size_t>(o.i)].name + "-" + r.strips[static_cast<std::size_t>(o.j)].name;
    if (!o.used) {
      add(out, "%-22s %10.1f   skipped: %s\n", name.c_str(), o.area, o.skip_reason.c_str());
      continue;
    }
    if (o.used_observations == 0) {
      add(out, "%-22s %10.1f   no observation (%zu conjugate points found, none used)\n", name.c_str(),
          o.area, o.observations);
      continue;
    }
    add(out, "%-22s %10.1f  %8zu / %-7zu  %8.4f   %10.4f %9.4f  ->  %10.4f %9.4f   %8.4f / %.4f\n",
        name.c_str(), o.area, o.used_observations, o.observations - o.used_observations, o.sigma0,
        o.before.rms, o.before.sigma_mad, o.after.rms, o.after.sigma_mad, o.noise_i.sigma_mad,
        o.noise_j.sigma_mad);
  }
  return out;
}

}  // namespace strips
}  // namespace pcl_ls3d
