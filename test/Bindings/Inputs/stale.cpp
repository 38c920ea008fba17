// Bindings in three versions for stale.test: one module "Stale" with one
// class whose thunk names stay the same from version to version.
//   (default)    v1: Body { float mass; short gear; }
//   -DLAYOUT2    v2: a field `id` in front: size and offsets change, the
//                    thunks keep their names
//   -DNO_SHIFT   v1 without the method `shift`: its thunk is gone
#include <bscript/Bind.h>

struct Body {
#ifdef LAYOUT2
  int id = 7;
#endif
  float mass = 0;
  short gear = 0;
  float weight() const { return 2 * mass; }
  int shift(int By) { return gear += By; }
};

#ifdef NO_SHIFT
BS_MODULE(Stale,
  registerClass<Body>(module, "Body")
    .var<&Body::mass>("mass")
    .var<&Body::gear>("gear")
    .func<&Body::weight>("weight");
)
#else
BS_MODULE(Stale,
  registerClass<Body>(module, "Body")
    .var<&Body::mass>("mass")
    .var<&Body::gear>("gear")
    .func<&Body::weight>("weight")
    .func<&Body::shift>("shift");
)
#endif
