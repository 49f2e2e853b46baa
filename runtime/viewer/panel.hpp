#pragma once
// The ImGui panel: frame time and rays/s, device memory by category, the camera (editable), every
// effect with its parameters (clip planes and box, AO rays/radius/samples, time and play), the
// camera path (keyframe count, step, add/play/clear, file name, save/load), the last pick, the
// screenshot button. It only edits ViewerState (touch() on every change that alters a frame; the
// path's file buttons read and write through path_recording); the main loop decides what to render.
#include <vector>

#include "runtime/placement/visibility.hpp"
#include "runtime/render/gpu_scene.hpp"
#include "runtime/viewer/camera_controller.hpp"
#include "runtime/viewer/viewer_state.hpp"

namespace nano::viewer {

struct PanelContext {
  const render::LoadReport* load = nullptr;  // device memory
  Bounds bounds;                             // slider ranges for planes and the clip box
  bool scripted = false;                     // the script drives the camera; the panel only shows
  std::vector<placement::HideableName> hideable;  // the scene's medium, compartments and molecule types: a switch each
};

// Issues the panel's widgets (between Overlay::begin_frame and end_frame).
void draw_panel(ViewerState& state, const PanelContext& context);

}  // namespace nano::viewer
