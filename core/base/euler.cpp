#include "base/euler.h"

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>

namespace dp {

glm::mat3 euler_xyz_deg(const vec3& deg) {
    const glm::mat4 id(1.0f);
    const glm::mat3 rx(glm::rotate(id, glm::radians(deg.x), vec3(1, 0, 0)));
    const glm::mat3 ry(glm::rotate(id, glm::radians(deg.y), vec3(0, 1, 0)));
    const glm::mat3 rz(glm::rotate(id, glm::radians(deg.z), vec3(0, 0, 1)));
    return rz * ry * rx;
}

vec3 euler_xyz_from_matrix(const glm::mat3& M) {
    constexpr double kDeg = 180.0 / std::numbers::pi;
    // M = Rz(g) Ry(b) Rx(a); glm indexes [column][row].
    const double sb = std::clamp(double(-M[0][2]), -1.0, 1.0);
    const double b = std::asin(sb);
    double a, g;
    if (std::abs(sb) < 0.99999) {
        a = std::atan2(double(M[1][2]), double(M[2][2]));
        g = std::atan2(double(M[0][1]), double(M[0][0]));
    } else {  // gimbal lock: only a - g (or a + g) is defined; put it all in g
        a = 0;
        g = std::atan2(double(-M[1][0]), double(M[1][1]));
    }
    return vec3(float(a * kDeg), float(b * kDeg), float(g * kDeg));
}

}  // namespace dp
