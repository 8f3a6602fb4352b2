#include "scene/character_collision.h"

#include <btBulletCollisionCommon.h>
#include <BulletCollision/CollisionDispatch/btGhostObject.h>
#include <BulletDynamics/Character/btKinematicCharacterController.h>

#include <cmath>

#include "core/error.h"

namespace glimmer {
namespace {
btVector3 bt(const glm::vec3& v) { return {v.x, v.y, v.z}; }
glm::vec3 glmOf(const btVector3& v) { return {float(v.x()), float(v.y()), float(v.z())}; }

// The nearest hit of a ray whose surface faces up (a floor), ignoring walls and ceilings along the way.
struct FloorRayCallback : btCollisionWorld::ClosestRayResultCallback {
    using ClosestRayResultCallback::ClosestRayResultCallback;
    btScalar addSingleResult(btCollisionWorld::LocalRayResult& result, bool normalInWorldSpace) override {
        if (result.m_hitNormalLocal.y() < 0.7071f && -result.m_hitNormalLocal.y() < 0.7071f) return m_closestHitFraction;
        // Triangles are stored with their winding as authored; a floor seen from above may face either way.
        return ClosestRayResultCallback::addSingleResult(result, normalInWorldSpace);
    }
};
}  // namespace

// Owns Bullet's objects in dependency order (members are destroyed bottom-up).
struct SceneCollision::Bullet {
    btTriangleMesh mesh{true, false};  // 32-bit indices, 3-float vertices
    std::unique_ptr<btBvhTriangleMeshShape> sceneShape;
    btCollisionObject sceneObject;
    btDefaultCollisionConfiguration configuration;
    btCollisionDispatcher dispatcher{&configuration};
    btDbvtBroadphase broadphase;
    btGhostPairCallback ghostPairs;
    std::unique_ptr<btCollisionWorld> world;
    std::unique_ptr<btCapsuleShape> capsule;
    btPairCachingGhostObject ghost;
    std::unique_ptr<btKinematicCharacterController> character;

    ~Bullet() {
        if (world) {
            world->removeCollisionObject(&ghost);
            world->removeCollisionObject(&sceneObject);
        }
    }
};

SceneCollision::SceneCollision(const Scene& scene, const StandingBody& body)
    : bullet_(std::make_unique<Bullet>()), body_(body) {
    Bullet& b = *bullet_;
    for (const Instance& instance : scene.instances) {
        const MeshData& mesh = scene.meshes.at(instance.mesh);
        for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            glm::vec3 p[3];
            for (int k = 0; k < 3; ++k) p[k] = glm::vec3(instance.transform * glm::vec4(mesh.positions.at(mesh.indices[i + size_t(k)]), 1.0f));
            if (glm::length(glm::cross(p[1] - p[0], p[2] - p[0])) <= 1e-12f) continue;  // degenerate
            b.mesh.addTriangle(bt(p[0]), bt(p[1]), bt(p[2]), false);
            ++triangles_;
        }
    }
    if (triangles_ == 0) throw Error("scene '" + scene.name + "': no triangles to walk on");
    b.sceneShape = std::make_unique<btBvhTriangleMeshShape>(&b.mesh, true);
    b.sceneObject.setCollisionShape(b.sceneShape.get());
    b.sceneObject.setCollisionFlags(btCollisionObject::CF_STATIC_OBJECT);
    b.broadphase.getOverlappingPairCache()->setInternalGhostPairCallback(&b.ghostPairs);
    b.world = std::make_unique<btCollisionWorld>(&b.dispatcher, &b.broadphase, &b.configuration);
    b.world->addCollisionObject(&b.sceneObject, btBroadphaseProxy::StaticFilter,
                                btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);

    b.capsule = std::make_unique<btCapsuleShape>(body.radius, body.height - 2.0f * body.radius);
    b.ghost.setCollisionShape(b.capsule.get());
    b.ghost.setCollisionFlags(btCollisionObject::CF_CHARACTER_OBJECT);
    b.world->addCollisionObject(&b.ghost, btBroadphaseProxy::CharacterFilter,
                                btBroadphaseProxy::StaticFilter | btBroadphaseProxy::DefaultFilter);
    b.character = std::make_unique<btKinematicCharacterController>(&b.ghost, b.capsule.get(), body.stepHeight,
                                                                   btVector3(0, 1, 0));
    b.character->setGravity(btVector3(0, -body.gravity, 0));
    b.character->setFallSpeed(body.maxFallSpeed);
    b.character->setMaxSlope(glm::radians(50.0f));
    // The character's sweeps allow the dispatcher's CCD penetration (0.04 m by default), which left the eye
    // 4 cm low after a fall: allow 1 mm.
    b.world->getDispatchInfo().m_allowedCcdPenetration = 0.001f;
    b.world->updateAabbs();
}

SceneCollision::~SceneCollision() = default;

std::optional<float> SceneCollision::floorBelow(const glm::vec3& point, float maxDistance) const {
    btVector3 from = bt(point), to = bt(point - glm::vec3(0.0f, maxDistance, 0.0f));
    FloorRayCallback hit(from, to);
    hit.m_collisionFilterGroup = btBroadphaseProxy::DefaultFilter;
    hit.m_collisionFilterMask = btBroadphaseProxy::StaticFilter;
    bullet_->world->rayTest(from, to, hit);
    if (!hit.hasHit()) return std::nullopt;
    return float(hit.m_closestHitFraction) * maxDistance;
}

bool SceneCollision::standingAt(const glm::vec3& eye, float tolerance) const {
    std::optional<float> down = floorBelow(eye, body_.eyeHeight + tolerance);
    return down && std::abs(*down - body_.eyeHeight) <= tolerance;
}

// The capsule's centre sits half its height above the feet; the eye eyeHeight above them.
void SceneCollision::placeEye(const glm::vec3& eye) {
    glm::vec3 feet = eye - glm::vec3(0.0f, body_.eyeHeight, 0.0f);
    // Feet a little inside a floor (a camera set slightly low): stand on the floor instead.
    if (std::optional<float> down = floorBelow(eye, body_.eyeHeight + body_.stepHeight); down && *down < body_.eyeHeight)
        feet.y = eye.y - *down;
    Bullet& b = *bullet_;
    b.character->reset(b.world.get());
    b.character->warp(bt(feet + glm::vec3(0.0f, 0.5f * body_.height, 0.0f)));
    b.world->updateSingleAabb(&b.ghost);
}

void SceneCollision::step(const glm::vec3& horizontalVelocity, float dt) {
    if (!(dt > 0.0f)) return;
    Bullet& b = *bullet_;
    glm::vec3 flat{horizontalVelocity.x, 0.0f, horizontalVelocity.z};
    b.character->setWalkDirection(bt(flat * dt));
    b.character->updateAction(b.world.get(), dt);
    b.world->updateSingleAabb(&b.ghost);
}

glm::vec3 SceneCollision::eye() const {
    glm::vec3 centre = glmOf(bullet_->ghost.getWorldTransform().getOrigin());
    return centre + glm::vec3(0.0f, body_.eyeHeight - 0.5f * body_.height, 0.0f);
}

bool SceneCollision::onGround() const { return bullet_->character->onGround(); }

}  // namespace glimmer
