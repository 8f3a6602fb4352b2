// Walking through a scene: a standing character (capsule) that falls under gravity onto floors, steps up small
// ledges, slides along walls and never passes through the scene's triangles. Collision queries and the character
// update are Bullet's (btBvhTriangleMeshShape over every instance's world-space triangles, built once per scene,
// and btKinematicCharacterController); this file only converts the scene and sets the standing dimensions.
#pragma once
#include <glm/glm.hpp>

#include <memory>
#include <optional>

#include "scene/scene.h"

namespace glimmer {

struct StandingBody {
    float eyeHeight = 1.7f;    // eye above the feet (metres)
    float radius = 0.3f;       // capsule radius: how close the eye gets to a wall
    float height = 1.8f;       // capsule height, feet to top of the head
    float stepHeight = 0.35f;  // ledges up to this high (stairs, kerbs) are climbed by walking into them
    float gravity = 9.81f;     // m/s^2
    float maxFallSpeed = 55.0f;
};

class SceneCollision {
public:
    // Builds the static triangle BVH of every instance (throws glimmer::Error for a scene without triangles).
    explicit SceneCollision(const Scene& scene, const StandingBody& body = {});
    ~SceneCollision();
    SceneCollision(const SceneCollision&) = delete;
    SceneCollision& operator=(const SceneCollision&) = delete;

    // The nearest upward-facing surface (normal within 45 degrees of up) straight below `point`, within
    // maxDistance: the distance down to it.
    std::optional<float> floorBelow(const glm::vec3& point, float maxDistance) const;
    // True when the eye at `eye` stands on a floor: one lies eyeHeight +- tolerance below it.
    bool standingAt(const glm::vec3& eye, float tolerance) const;

    // Places the character with its eye at `eye` (or on the floor under it when the feet would be inside it)
    // and stops any fall.
    void placeEye(const glm::vec3& eye);
    // One update: walks by horizontalVelocity * dt (the vertical part is ignored: gravity decides), colliding.
    void step(const glm::vec3& horizontalVelocity, float dt);
    glm::vec3 eye() const;
    bool onGround() const;
    const StandingBody& body() const { return body_; }
    size_t triangleCount() const { return triangles_; }

private:
    struct Bullet;
    std::unique_ptr<Bullet> bullet_;
    StandingBody body_;
    size_t triangles_ = 0;
};

}  // namespace glimmer
