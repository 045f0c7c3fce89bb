// panel.cpp: the viewer's panel (Dear ImGui) and its keys. Every setting of `vgeo render` that changes
// a frame is here, so what the window shows can be written down as a command line (the camera too:
// "print camera").
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "../renderer/debug_modes.h"
#include "view_state.h"

namespace vgeo {

namespace {

const char* kOcclusionNames[] = {"off", "on", "auto"};  // Occlusion's order

}  // namespace

void drawFrozenFrustum(const View& frozen, const View& draw, float farDistance) {
  // The frozen camera's frustum from its near plane to farDistance (reversed depth: z = znear / depth),
  // its corners in world space, its edges clipped in front of the draw camera and drawn over the picture.
  const glm::mat4 toWorld = glm::inverse(frozen.viewProjection);
  glm::vec3 corners[8];
  for (int i = 0; i < 8; i++) {
    const glm::vec4 p = toWorld * glm::vec4(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f,
                                            i & 4 ? frozen.znear / std::max(farDistance, frozen.znear) : 1.0f, 1.0f);
    corners[i] = glm::vec3(p) / p.w;
  }
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  ImDrawList* lines = ImGui::GetBackgroundDrawList();
  auto screen = [&](glm::vec4 c) {
    return ImVec2((c.x / c.w * 0.5f + 0.5f) * size.x, (c.y / c.w * 0.5f + 0.5f) * size.y);
  };
  const int edges[12][2] = {{0, 1}, {2, 3}, {0, 2}, {1, 3}, {4, 5}, {6, 7},
                            {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for (const auto& e : edges) {
    glm::vec4 a = draw.viewProjection * glm::vec4(corners[e[0]], 1.0f),
              b = draw.viewProjection * glm::vec4(corners[e[1]], 1.0f);
    const float near = draw.znear;  // clip where the segment passes behind the draw camera's near plane
    if (a.w < near && b.w < near) continue;
    if (a.w < near) a = glm::mix(a, b, (near - a.w) / (b.w - a.w));
    if (b.w < near) b = glm::mix(b, a, (near - b.w) / (a.w - b.w));
    lines->AddLine(screen(a), screen(b), IM_COL32(255, 210, 60, 255), 1.5f);
  }
}

void drawPanel(ViewState& s, const ViewStats& stats) {
  if (!s.panel) return;
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  // Its height follows what it holds, every frame (a view's legend or the pyramid's slider come and go).
  ImGui::SetNextWindowSize(ImVec2(480, 0), ImGuiCond_Always);
  ImGui::Begin("vgeo");
  const FrameResult& f = stats.frame;
  const auto& c = f.counters;
  ImGui::Text("%s, %ux%u", stats.device.c_str(), stats.width, stats.height);
  ImGui::Text("frame %.2f ms (%.0f fps), GPU passes %.2f ms (%s)", stats.frameMs,
              stats.frameMs > 0 ? 1000.0 / stats.frameMs : 0.0, f.frameMs, f.timing.c_str());
  ImGui::Text("cull %.3f  traverse %.3f  triangles %.3f", f.instanceCullMs, f.traversalMs, f.triangleCullMs);
  ImGui::Text("raster %.3f  draw %.3f  resolve %.3f  pyramid %.3f", f.rasterMs, f.drawMs, f.resolveMs, f.pyramidMs);
  ImGui::Text("instances %u visible, clusters %u, triangles %u", c.visibleInstances, c.drawCount, f.trianglesDrawn);
  ImGui::Text("patches %u, queue high water %u", f.patchesDrawn, c.queueHighWater);
  if (f.occlusion)
    ImGui::Text("two passes: hidden %u instances, %u nodes, %u clusters", c.occludedInstances, c.occludedNodes,
                c.occludedClusters);
  if (!f.complete)
    ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "overflow: queue %u, draw %u, triangles %u, patches %u (grown)",
                       c.queueOverflow, c.drawOverflow, c.triangleOverflow, c.patchOverflow);
  ImGui::Separator();
  int mode = 0;
  for (size_t i = 0; i < std::size(kDebugModes); i++)
    if (kDebugModes[i].mode == s.frame.mode) mode = int(i);
  if (ImGui::BeginCombo("view [M]", kDebugModes[mode].name)) {
    for (size_t i = 0; i < std::size(kDebugModes); i++)
      if (ImGui::Selectable(kDebugModes[i].name, int(i) == mode)) s.frame.mode = kDebugModes[i].mode;
    ImGui::EndCombo();
  }
  ImGui::TextWrapped("%s", kDebugModes[mode].legend);
  if (s.frame.mode == VGEO_MODE_LOD) ImGui::Text("blue level 0, red level %u", std::max(stats.lodLevels, 2u) - 1);
  if (s.frame.mode == VGEO_MODE_PYRAMID) {
    int level = int(s.frame.pyramidViewLevel);
    if (ImGui::SliderInt("pyramid level", &level, 1, 12)) s.frame.pyramidViewLevel = uint32_t(level);
  }
  ImGui::SliderFloat("tau [+ -]", &s.frame.tau, 0.05f, 64.0f, "%.2f px", ImGuiSliderFlags_Logarithmic);
  int occlusion = int(s.frame.occlusion);
  if (ImGui::Combo("occlusion [O]", &occlusion, kOcclusionNames, 3)) s.frame.occlusion = Occlusion(occlusion);
  int traversal = int(s.frame.traversal);
  const char* traversals[] = {"persistent", "levels", "flat"};
  if (ImGui::Combo("traversal", &traversal, traversals, 3)) s.frame.traversal = Traversal(traversal);
  int culling = int(s.frame.instanceCulling);
  const char* cullings[] = {"auto", "pass", "traversal"};
  if (ImGui::Combo("instance culling", &culling, cullings, 3)) s.frame.instanceCulling = InstanceCulling(culling);
  ImGui::Checkbox("triangle culling [T]", &s.frame.triangleCull);
  ImGui::Checkbox("patches [P]", &s.frame.patches);
  ImGui::Checkbox("headlight [L] (else the fixed light)", &s.headlight);
  bool frozen = s.frozen;
  if (ImGui::Checkbox("freeze the cut [F]", &frozen)) pressKey(s, "F");
  if (ImGui::Button("screenshot [F12]")) pressKey(s, "F12");
  ImGui::SameLine();
  if (ImGui::Button("print camera [C]")) pressKey(s, "C");
  if (!stats.lastScreenshot.empty()) ImGui::Text("wrote %s", stats.lastScreenshot.c_str());
  ImGui::SliderFloat("speed", &s.camera.speed, 1e-3f, 1e6f, "%.3g/s", ImGuiSliderFlags_Logarithmic);
  ImGui::TextWrapped("WASD fly, Q/E down/up, right mouse look, scroll speed, H home, Tab hides this, Esc quit");
  ImGui::End();
}

}  // namespace vgeo
