#include "runtime/oracle/explicit_scene.hpp"

namespace nano::oracle {

struct ExplicitScene::Impl : format::PackageView {
  placement::CopyEnumerator copies;
  Impl(const format::Package& package, const ExplicitSceneOptions& options) : PackageView(package), copies(package, options) {}
};

ExplicitScene::ExplicitScene(const format::Package& package, const ExplicitSceneOptions& options)
    : impl_(std::make_unique<Impl>(package, options)) {}
ExplicitScene::~ExplicitScene() = default;
ExplicitScene::ExplicitScene(ExplicitScene&&) noexcept = default;

const std::vector<format::InstanceTransform>& ExplicitScene::instance_transforms() const {
  return impl_->copies.instance_transforms();
}
std::uint64_t ExplicitScene::copy_number_limit() const { return impl_->copies.copy_number_limit(); }

void ExplicitScene::for_each_copy(const WorldBox& box, const std::function<void(const Copy&)>& visit) const {
  impl_->copies.for_each_copy(box, visit);
}

void ExplicitScene::for_each_copy_of(std::uint32_t i, const WorldBox& box, const std::function<void(const Copy&)>& visit) const {
  impl_->copies.for_each_copy_of(i, box, visit);
}

void ExplicitScene::for_each_membrane_copy(std::uint32_t i, std::uint32_t triangle,
                                           const std::function<void(const Copy&)>& visit) const {
  impl_->copies.for_each_membrane_copy(i, triangle, visit);
}

bool ExplicitScene::has_medium() const { return impl_->copies.has_medium(); }

void ExplicitScene::for_each_medium_copy(const glm::ivec3& box, const std::function<void(const Copy&)>& visit,
                                         const placement::CopyEnumerator::SphereTest& may_meet) const {
  impl_->copies.for_each_medium_copy(box, WorldBox::everything(), visit, may_meet);
}

namespace {

// The atoms of one copy whose centres lie in `box`.
void visit_atoms(const format::PackageView& s, const WorldBox& box, const Copy& copy,
                 const std::function<void(const AtomSample&)>& visit) {
  const gpu::MoleculeType& type = s.molecules[copy.molecule_type];
  AtomSample sample;
  sample.copy = &copy;
  for (std::uint32_t a = type.first_atom; a < type.first_atom + type.atom_count; ++a) {
    sample.position = copy.origin + copy.linear * glm::dvec3(s.atoms[a].centre_radius);
    if (!box.contains(sample.position)) continue;
    sample.atom = a;
    sample.info = s.atom_info.empty() ? nullptr : &s.atom_info[a];
    sample.radius = s.atoms[a].centre_radius.w * copy.stretch;
    visit(sample);
  }
}

}  // namespace

void ExplicitScene::for_each_compartment_atom(const WorldBox& box, const std::function<void(const AtomSample&)>& visit) const {
  for_each_copy(box, [&](const Copy& copy) { visit_atoms(*impl_, box, copy, visit); });
}

void ExplicitScene::for_each_atom(const WorldBox& box, const std::function<void(const AtomSample&)>& visit,
                                  std::uint64_t max_medium_boxes) const {
  for_each_compartment_atom(box, visit);
  impl_->copies.for_each_medium_copy(box, [&](const Copy& copy) { visit_atoms(*impl_, box, copy, visit); }, max_medium_boxes);
}

}  // namespace nano::oracle
