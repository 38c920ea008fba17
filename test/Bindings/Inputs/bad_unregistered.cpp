// Eigen's dot() takes `const MatrixBase<D>&`, a type no module registers.
#include <Eigen/Dense>
#include <bscript/Bind.h>
using Eigen::Vector2f;
BS_MODULE(BadDot,
  registerClass<Vector2f>(module, "Vector2f", "Eigen::Vector2f")
    .func<&Vector2f::dot<Vector2f>>("dot");
)
