// A free-flight camera over the water: position, yaw and pitch in degrees, z up.
#pragma once

#include <glm/glm.hpp>

namespace heightpack::view {

struct Camera {
    glm::vec3 position{0.0f, 0.0f, 8.0f};
    float yaw = 30.0f;     // degrees from +x toward +y
    float pitch = -10.0f;  // degrees above the horizon
    float fovY = 60.0f;    // degrees

    glm::vec3 forward() const;
    glm::mat4 view() const;
    glm::mat4 projection(float aspect) const;
    // Flight: move is (forward, right, up) in -1..1, seconds elapsed; speed grows with altitude so a
    // person gets from a ripple to high above the sea in a few seconds.
    void fly(glm::vec3 move, float seconds);
    void look(float dxPixels, float dyPixels);
};

}  // namespace heightpack::view
