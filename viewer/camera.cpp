#include "camera.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace heightpack::view {

glm::vec3 Camera::forward() const {
    const float y = glm::radians(yaw), p = glm::radians(pitch);
    return {std::cos(p) * std::cos(y), std::cos(p) * std::sin(y), std::sin(p)};
}

glm::mat4 Camera::view() const { return glm::lookAt(position, position + forward(), glm::vec3(0, 0, 1)); }

glm::mat4 Camera::projection(float aspect) const {
    // The far plane reaches past the grid's 40 km rim; the near plane follows the altitude so depth
    // precision is spent where the water is.
    const float nearPlane = std::clamp(std::abs(position.z) * 0.01f, 0.02f, 5.0f);
    return glm::perspective(glm::radians(fovY), aspect, nearPlane, 60000.0f);
}

void Camera::fly(glm::vec3 move, float seconds) {
    const float speed = std::max(2.0f, std::abs(position.z) * 1.5f);
    const glm::vec3 f = forward();
    const glm::vec3 right = glm::normalize(glm::cross(f, glm::vec3(0, 0, 1)));
    position += (f * move.x + right * move.y + glm::vec3(0, 0, 1) * move.z) * speed * seconds;
}

void Camera::look(float dxPixels, float dyPixels) {
    yaw -= dxPixels * 0.15f;
    pitch = std::clamp(pitch - dyPixels * 0.15f, -89.0f, 89.0f);
}

}  // namespace heightpack::view
