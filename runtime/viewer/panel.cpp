#include "runtime/viewer/panel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <imgui.h>

#include "runtime/render/effects.hpp"
#include "runtime/render/pick_info.hpp"
#include "runtime/viewer/path_recording.hpp"

namespace nano::viewer {
namespace {

std::string megabytes(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f MB", double(bytes) / 1e6);
  return text;
}

void frame_section(const ViewerState& s, const PanelContext& c) {
  const FrameStats& f = s.stats;
  ImGui::Text("frame %.3f s  %ux%u%s", f.seconds, f.width, f.height, f.scale > 1 ? " (moving)" : "");
  ImGui::Text("%.2f Mrays/s", f.rays_per_second / 1e6);
  if (s.settings.effects.flag(EffectId::ambient_occlusion)) ImGui::Text("AO samples %u / %u", f.samples, s.ao_samples);
  if (c.load) {
    const render::MemoryReport& m = c.load->memory;
    if (ImGui::TreeNode("device memory", "device memory %s", megabytes(m.total()).c_str())) {
      ImGui::Text("package   %s", megabytes(m.package_data).c_str());
      ImGui::Text("imported  %s (mapped file)", megabytes(m.package_imported).c_str());
      ImGui::Text("derived   %s", megabytes(m.derived).c_str());
      ImGui::Text("nLAS      %s", megabytes(m.nlas).c_str());
      ImGui::Text("mLAS      %s", megabytes(m.mlas).c_str());
      ImGui::Text("uLAS      %s", megabytes(m.ulas).c_str());
      ImGui::Text("scratch peak %s (freed)", megabytes(m.scratch_peak).c_str());
      ImGui::TreePop();
    }
  }
}

void camera_section(ViewerState& s, const PanelContext& c) {
  if (!ImGui::CollapsingHeader("camera")) return;
  int mode = s.camera.mode() == CameraController::Mode::orbit ? 0 : 1;
  if (ImGui::RadioButton("orbit", &mode, 0) | (ImGui::SameLine(), ImGui::RadioButton("fly (Tab)", &mode, 1)))
    s.camera.set_mode(mode == 0 ? CameraController::Mode::orbit : CameraController::Mode::fly);
  Camera camera = s.camera.camera();
  bool changed = false;
  changed |= ImGui::InputScalarN("position", ImGuiDataType_Double, &camera.position, 3, nullptr, nullptr, "%.1f",
                                 ImGuiInputTextFlags_EnterReturnsTrue);
  changed |= ImGui::InputScalarN("look_at", ImGuiDataType_Double, &camera.look_at, 3, nullptr, nullptr, "%.1f",
                                 ImGuiInputTextFlags_EnterReturnsTrue);
  const double fov_min = 1, fov_max = 150;
  changed |= ImGui::SliderScalar("fov_degrees", ImGuiDataType_Double, &camera.fov_degrees, &fov_min, &fov_max, "%.1f°");
  ImGui::Text("distance %.1f Å, fly speed %.1f Å/s", s.camera.distance(), s.camera.fly_speed());
  if (ImGui::Button("reset view")) {
    // Looks at the whole scene from the current direction.
    const glm::dvec3 dir = glm::normalize(camera.position - camera.look_at);
    camera.look_at = c.bounds.centre();
    camera.position = camera.look_at + dir * (c.bounds.radius() / std::tan(glm::radians(camera.fov_degrees) * 0.5));
    changed = true;
  }
  if (changed && !c.scripted) {
    if (const std::string wrong = camera.problem(); !wrong.empty()) {
      s.status = wrong;  // the edit is not taken; the session goes on
    } else {
      s.camera.set_camera(camera);
      s.touch();
    }
  }
}

void clipping_section(ViewerState& s, const PanelContext& c) {
  render::EffectSettings& e = s.settings.effects;
  bool changed = false;
  const double r = std::max(c.bounds.radius(), 1.0);
  const glm::dvec3 centre = c.bounds.centre();
  for (std::size_t i = 0; i < e.clipping.planes.size(); ++i) {
    ImGui::PushID(int(i));
    glm::dvec4& p = e.clipping.planes[i];
    const double n_min = -1, n_max = 1, d_min = -2 * r - glm::length(centre), d_max = 2 * r + glm::length(centre);
    ImGui::Text("plane %zu", i);
    changed |= ImGui::SliderScalarN("normal", ImGuiDataType_Double, &p, 3, &n_min, &n_max, "%.2f");
    changed |= ImGui::SliderScalar("d (Å)", ImGuiDataType_Double, &p.w, &d_min, &d_max, "%.1f");
    if (glm::length(glm::dvec3(p)) == 0) p.x = 1;  // a zero normal clips nothing sensible
    if (ImGui::Button("remove")) {
      e.clipping.planes.erase(e.clipping.planes.begin() + std::ptrdiff_t(i));
      changed = true;
      ImGui::PopID();
      break;
    }
    ImGui::PopID();
  }
  if (e.clipping.planes.size() < render::kMaxClipPlanes && ImGui::Button("add plane")) {
    // Through the scene centre facing the camera: it removes the near half.
    const glm::dvec3 n = glm::normalize(s.camera.camera().look_at - s.camera.camera().position);
    e.clipping.planes.emplace_back(n, -glm::dot(n, centre));
    e.flag(EffectId::clipping) = changed = true;
  }
  bool box = e.clipping.box.has_value();
  if (ImGui::Checkbox("clip box", &box)) {
    if (box) e.clipping.box = std::pair(c.bounds.lo, c.bounds.hi);
    else e.clipping.box.reset();
    if (box) e.flag(EffectId::clipping) = true;
    changed = true;
  }
  if (e.clipping.box) {
    const double lo = -2 * r + std::min({centre.x, centre.y, centre.z}), hi = 2 * r + std::max({centre.x, centre.y, centre.z});
    changed |= ImGui::SliderScalarN("box min", ImGuiDataType_Double, &e.clipping.box->first, 3, &lo, &hi, "%.0f");
    changed |= ImGui::SliderScalarN("box max", ImGuiDataType_Double, &e.clipping.box->second, 3, &lo, &hi, "%.0f");
    for (int a = 0; a < 3; ++a)  // keep min < max so the box never becomes invalid
      e.clipping.box->second[a] = std::max(e.clipping.box->second[a], e.clipping.box->first[a] + 1);
  }
  if (changed) s.touch();
}

// The widget the effect table names for a parameter, on its slot of the settings' record; true when
// the user changed it.
bool parameter_widget(const EffectParameter& p, gpu::SceneEffects& record) {
  std::string label(p.key);
  if (!p.unit.empty()) label += " (" + std::string(p.unit) + ")";
  switch (p.widget) {
    case PanelWidget::slider:
    case PanelWidget::log_slider: {
      const ImGuiSliderFlags flags = p.widget == PanelWidget::log_slider ? ImGuiSliderFlags_Logarithmic : 0;
      const char* format = p.kind == ParameterKind::whole_number ? "%.0f" : "%.2f";
      float& value = number_slot(record, p);
      if (!ImGui::SliderFloat(label.c_str(), &value, float(p.panel_min), float(p.panel_max), format, flags)) return false;
      if (p.kind == ParameterKind::whole_number) value = std::round(value);
      return true;
    }
    case PanelWidget::direction: {
      glm::vec3& direction = direction_slot(record, p);
      glm::vec3 v = direction;
      if (!ImGui::SliderFloat3(label.c_str(), &v.x, float(p.panel_min), float(p.panel_max), "%.2f")) return false;
      if (glm::length(v) > 0) direction = glm::vec3(glm::normalize(glm::dvec3(v)));  // a zero vector keeps the last direction
      return true;
    }
    case PanelWidget::colour_picker: {
      std::uint32_t& colour = colour_slot(record, p);
      glm::vec3 v(unpack_colour(colour));
      if (!ImGui::ColorEdit3(label.c_str(), &v.x)) return false;
      colour = pack_colour(glm::dvec3(v));  // clamps to [0, 1]
      return true;
    }
  }
  return false;
}

// One switch per thing the scene can leave out: its medium, each compartment (all its instances),
// each molecule type wherever it stands; the names render --hide takes.
void show_section(ViewerState& s, const PanelContext& c) {
  if (c.hideable.empty() || !ImGui::CollapsingHeader("show")) return;
  using Kind = placement::HideableName::Kind;
  for (const placement::HideableName& n : c.hideable) {
    const bool shared = placement::hideable_matches(c.hideable, n.name) > 1;
    const std::string name = shared ? std::string(n.kind == Kind::compartment ? "compartment:" : "molecule:") + n.name : n.name;
    const std::string label = n.kind == Kind::medium        ? "medium (between the compartments)"
                              : n.kind == Kind::compartment ? "compartment " + n.name + " (every instance)"
                                                            : "molecule " + n.name;
    bool on = render::shown(s.settings, name);
    if (ImGui::Checkbox(label.c_str(), &on)) {
      render::set_shown(s.settings, name, on);
      s.touch();
    }
  }
}

void effects_section(ViewerState& s, const PanelContext& c) {
  if (!ImGui::CollapsingHeader("effects")) return;
  render::EffectSettings& e = s.settings.effects;
  for (const EffectPreset& preset : effect_presets()) {
    if (ImGui::Button(std::string(preset.name).c_str())) {
      render::apply_preset(e, preset);
      s.touch();
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", std::string(preset.summary).c_str());
    ImGui::SameLine();
  }
  ImGui::NewLine();
  for (const EffectDeclaration& effect : effect_table())
    if (ImGui::Checkbox(std::string(effect.name).c_str(), &e.flag(effect.id))) s.touch();
  if (ImGui::TreeNode("clipping planes and box")) {
    clipping_section(s, c);
    ImGui::TreePop();
  }
  for (const EffectDeclaration& effect : effect_table()) {
    if (effect.parameters.empty() || !ImGui::TreeNode(std::string(effect.name).c_str())) continue;
    for (const EffectParameter& p : effect.parameters)
      if (parameter_widget(p, e.record)) s.touch();
    if (effect.id == EffectId::ambient_occlusion) {
      const std::uint32_t samples_min = 1, samples_max = 256;
      ImGui::SliderScalar("samples", ImGuiDataType_U32, &s.ao_samples, &samples_min, &samples_max);
    }
    ImGui::TreePop();
  }
  const double t_min = 0, t_max = std::max(60.0, e.time);
  if (ImGui::SliderScalar("time (s)", ImGuiDataType_Double, &e.time, &t_min, &t_max, "%.2f")) s.touch();
  if (ImGui::Button(s.playing ? "pause" : "play")) s.playing = !s.playing;
  ImGui::SameLine();
  const double speed_min = 0.01, speed_max = 100;
  ImGui::SetNextItemWidth(120);
  ImGui::SliderScalar("speed", ImGuiDataType_Double, &s.play_speed, &speed_min, &speed_max, "%.2fx", ImGuiSliderFlags_Logarithmic);
}

// ImGui::InputText on a std::string (Debian's libimgui lacks misc/cpp/imgui_stdlib): the callback
// grows the string when the text outgrows its buffer.
bool input_string(const char* label, std::string& text) {
  const auto resize = [](ImGuiInputTextCallbackData* data) {
    if (data->EventFlag == ImGuiInputTextFlags_CallbackResize) {
      auto* string = static_cast<std::string*>(data->UserData);
      string->resize(std::size_t(data->BufTextLen));
      data->Buf = string->data();
    }
    return 0;
  };
  return ImGui::InputText(label, text.data(), text.capacity() + 1, ImGuiInputTextFlags_CallbackResize, resize, &text);
}

void path_section(ViewerState& s) {
  if (!ImGui::CollapsingHeader("camera path (K adds, L plays)")) return;
  PathRecording& r = s.path;
  if (r.path.keyframes.empty()) ImGui::TextDisabled("no keyframes");
  else
    ImGui::Text("%zu keyframe(s), %.2f s, %llu frames at %g fps", r.path.keyframes.size(), r.path.duration(),
                (unsigned long long)r.path.frame_count(), r.path.fps);
  if (r.play_time) ImGui::Text("playing %.2f / %.2f s", *r.play_time, r.path.duration());
  const double step_min = 0.1, step_max = 60;
  ImGui::SliderScalar("step (s)", ImGuiDataType_Double, &r.step, &step_min, &step_max, "%.2f", ImGuiSliderFlags_Logarithmic);
  r.step = std::clamp(r.step, step_min, step_max);  // Ctrl+click typing can leave the range
  if (ImGui::Button("Add keyframe (K)")) record_keyframe(s);
  ImGui::SameLine();
  ImGui::TextDisabled("at %.2f s", next_keyframe_time(r.path, r.step));
  if (ImGui::Button(r.play_time ? "Stop path (L)" : "Play path (L)")) toggle_playback(s);
  ImGui::SameLine();
  if (ImGui::Button("Clear")) clear_recording(s);
  input_string("file", r.file);
  if (ImGui::Button("Save path")) save_recording(s);
  ImGui::SameLine();
  if (ImGui::Button("Load path")) load_recording(s);
}

void pick_section(const ViewerState& s) {
  if (!ImGui::CollapsingHeader("pick (click)", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (!s.last_pick) {
    ImGui::TextDisabled("click a pixel");
    return;
  }
  const std::string text = render::describe_hit_text(*s.last_pick);
  ImGui::Text("pixel %d, %d", s.last_pick->value("x", 0), s.last_pick->value("y", 0));
  ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 320);  // the panel sizes itself; wrap at a fixed width
  ImGui::TextUnformatted(text.c_str());
  ImGui::PopTextWrapPos();
}

}  // namespace

void draw_panel(ViewerState& s, const PanelContext& c) {
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.8f);
  // Grows and shrinks with the open sections, so the status line below them is always in view.
  if (ImGui::Begin(c.scripted ? "nanoview (scripted)" : "nanoview", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::PushItemWidth(220);
    frame_section(s, c);
    // A script drives the state; the panel only shows it, so a stray click cannot change a screenshot.
    ImGui::BeginDisabled(c.scripted);
    camera_section(s, c);
    show_section(s, c);
    effects_section(s, c);
    path_section(s);
    pick_section(s);
    if (ImGui::Button("screenshot (F12, P)")) s.screenshot_requested = true;
    ImGui::EndDisabled();
    if (!s.compiling.empty()) ImGui::Text("%s", s.compiling.c_str());
    if (!s.status.empty()) ImGui::Text("%s", s.status.c_str());
    ImGui::PopItemWidth();
  }
  ImGui::End();
}

}  // namespace nano::viewer
