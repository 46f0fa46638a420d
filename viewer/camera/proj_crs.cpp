// PROJ wrapper (see proj_crs.hpp).
#include "camera/proj_crs.hpp"

#include <proj.h>

#include <cmath>

#include "runtime/errors.hpp"

namespace globe::viewer {
namespace {

struct ContextFree {
  void operator()(PJ_CONTEXT* c) const { proj_context_destroy(c); }
};
struct PjFree {
  void operator()(PJ* p) const { proj_destroy(p); }
};
using Context = std::unique_ptr<PJ_CONTEXT, ContextFree>;
using Pj = std::unique_ptr<PJ, PjFree>;

Context new_context() {
  Context ctx(proj_context_create());
  if (!ctx) throw InputError("PROJ: cannot create a context (out of memory?)");
  proj_log_level(ctx.get(), PJ_LOG_NONE);  // errors are reported below, with their context
  return ctx;
}

std::string last_error(PJ_CONTEXT* ctx) {
  const char* msg = proj_context_errno_string(ctx, proj_context_errno(ctx));
  return msg ? msg : "unknown PROJ error";
}

Pj crs_of(PJ_CONTEXT* ctx, const std::string& text, const std::string& context) {
  Pj crs(proj_create(ctx, text.c_str()));
  if (!crs || !proj_is_crs(crs.get()))
    throw InputError(context + ": its CRS is not one PROJ can read (" + last_error(ctx) +
                     "); rebuild the package with a valid --t_srs or --s_srs");
  return crs;
}

}  // namespace

struct ProjTransform::Impl {
  Context ctx;
  Pj op;
};

ProjTransform::ProjTransform(const std::string& from_crs, const std::string& to_crs,
                             const std::string& context)
    : impl_(std::make_unique<Impl>()) {
  impl_->ctx = new_context();
  PJ_CONTEXT* ctx = impl_->ctx.get();
  const Pj from = crs_of(ctx, from_crs, context), to = crs_of(ctx, to_crs, context);
  Pj op(proj_create_crs_to_crs_from_pj(ctx, from.get(), to.get(), nullptr, nullptr));
  if (!op)
    throw InputError(context + ": PROJ finds no transformation between its CRS and lon/lat (" +
                     last_error(ctx) + ")");
  impl_->op.reset(proj_normalize_for_visualization(ctx, op.get()));
  if (!impl_->op)
    throw InputError(context + ": PROJ cannot order the transformation's axes (" + last_error(ctx) +
                     ")");
}

ProjTransform::~ProjTransform() = default;

bool ProjTransform::transform(double& x, double& y) const {
  proj_errno_reset(impl_->op.get());
  const PJ_COORD out = proj_trans(impl_->op.get(), PJ_FWD, proj_coord(x, y, 0, 0));
  if (proj_errno(impl_->op.get()) != 0 || !std::isfinite(out.xy.x) || !std::isfinite(out.xy.y) ||
      out.xy.x == HUGE_VAL || out.xy.y == HUGE_VAL)
    return false;
  x = out.xy.x;
  y = out.xy.y;
  return true;
}

bool crs_is_geographic(const std::string& crs, const std::string& context) {
  const Context ctx = new_context();
  Pj pj = crs_of(ctx.get(), crs, context);
  if (proj_get_type(pj.get()) == PJ_TYPE_BOUND_CRS)
    pj.reset(proj_get_source_crs(ctx.get(), pj.get()));
  if (!pj)
    throw InputError(context + ": PROJ cannot read its CRS's base (" + last_error(ctx.get()) + ")");
  const PJ_TYPE t = proj_get_type(pj.get());
  return t == PJ_TYPE_GEOGRAPHIC_CRS || t == PJ_TYPE_GEOGRAPHIC_2D_CRS ||
         t == PJ_TYPE_GEOGRAPHIC_3D_CRS;
}

bool crs_equivalent(const std::string& a, const std::string& a_context, const std::string& b,
                    const std::string& b_context) {
  const Context ctx = new_context();
  const Pj pa = crs_of(ctx.get(), a, a_context), pb = crs_of(ctx.get(), b, b_context);
  return proj_is_equivalent_to_with_ctx(ctx.get(), pa.get(), pb.get(),
                                        PJ_COMP_EQUIVALENT_EXCEPT_AXIS_ORDER_GEOGCRS) != 0;
}

}  // namespace globe::viewer
