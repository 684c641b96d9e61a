// kinlib's 3-D scene view: one meshcat viewer (three.js) inside a page element.
//
// The same code runs in two places: in the notebook, as the view of the Scene widget
// (kinlib/viz/_widget.py appends the anywidget entry point), and in exported pages, where
// kinlib.site (and RobotVisualizer.static_html) call kinlibStaticScenes() on the scenes
// saved with the notebook. Commands are meshcat's own msgpack messages; poses come as one
// Float32Array of column-major 4x4 matrices, one per path.

function kinlibBytes(v) {
  // a widget buffer (DataView), an ArrayBuffer or a typed array, as a Uint8Array
  if (v instanceof Uint8Array) return v;
  if (ArrayBuffer.isView(v)) return new Uint8Array(v.buffer, v.byteOffset, v.byteLength);
  return new Uint8Array(v);
}

function kinlibFloats(v) {
  // a Float32Array over a copy (a buffer's offset need not be a multiple of 4)
  const bytes = kinlibBytes(v);
  return new Float32Array(bytes.slice().buffer);
}

function kinlibSameBytes(a, b) {
  if (a.byteLength !== b.byteLength) return false;
  for (let i = 0; i < a.byteLength; i++) if (a[i] !== b[i]) return false;
  return true;
}

function kinlibSplit(path) {
  return path.split("/").filter((x) => x.length > 0);
}

function kinlibMountScene(MeshCat, el, height) {
  // A meshcat viewer in `el`, `height` pixels tall. Returns its controller.
  const wrap = document.createElement("div");
  wrap.className = "kinlib-scene";
  wrap.style.cssText = "position: relative; width: 100%; overflow: hidden;";
  wrap.style.height = `${height}px`;
  const pane = document.createElement("div");
  pane.style.cssText = "width: 100%; height: 100%;";
  wrap.appendChild(pane);
  el.appendChild(wrap);
  const viewer = new MeshCat.Viewer(pane, false); // false: kinlib runs the render loop
  viewer.animate = () => {}; // (meshcat restarts its own loop after a recording: not here)
  let alive = true;
  const fit = viewer.set_3d_pane_size.bind(viewer);
  // meshcat sizes its pane to the window; a cell's viewer follows its own element
  viewer.set_3d_pane_size = (w, h) => {
    if (!alive) return;
    const width = w === undefined ? pane.clientWidth : w;
    const tall = h === undefined ? pane.clientHeight : h;
    if (width > 0 && tall > 0) fit(width, tall);
  };
  const resize = new ResizeObserver(() => viewer.set_3d_pane_size());
  resize.observe(pane);
  const stats = { commands: 0, poses: 0, drawn: 0, renders: 0, ticks: 0, seq: -1, log: [] };
  let pending = false;
  let frame = 0;
  // The loop runs only while there is something to draw: a frame is asked for when meshcat
  // marks the scene dirty (a command, a pose, the mouse orbiting, a resize) or an animation
  // starts to play (while it plays, meshcat's animator marks the scene dirty every frame),
  // and no more once a frame has nothing to draw. An idle viewer costs no CPU (a loop
  // running at the display's rate cost about a tenth of a core per viewer in headless
  // Chromium, and drains a laptop's battery as well).
  function tick() {
    frame = 0;
    if (!alive) return;
    stats.ticks += 1; // display frames this viewer used
    viewer.animator.update();
    if (viewer.needs_render) {
      viewer.render();
      stats.renders += 1;
      if (pending) {
        // a pose update reached the screen
        pending = false;
        stats.drawn += 1;
        if (stats.log.length < 100000) stats.log.push([stats.seq, Date.now()]);
        wrap.dataset.framesDrawn = String(stats.drawn);
        wrap.dataset.lastSeqDrawn = String(stats.seq);
      }
    }
  }
  function wake() {
    if (alive && !frame) frame = requestAnimationFrame(tick);
  }
  const markDirty = viewer.set_dirty.bind(viewer);
  viewer.set_dirty = () => {
    markDirty();
    wake();
  };
  const play = viewer.animator.play.bind(viewer.animator);
  viewer.animator.play = () => {
    play();
    wake();
  };
  wake();
  const controller = {
    viewer,
    stats,
    commands(list) {
      for (const c of list) viewer.handle_command_bytearray(kinlibBytes(c));
      stats.commands += list.length;
      viewer.set_dirty();
    },
    poses(paths, matrices, seq) {
      const m = matrices instanceof Float32Array ? matrices : kinlibFloats(matrices);
      const n = Math.min(paths.length, Math.floor(m.length / 16));
      for (let i = 0; i < n; i++) {
        viewer.set_transform(kinlibSplit(paths[i]), m.subarray(16 * i, 16 * i + 16));
      }
      stats.poses += 1;
      stats.seq = seq === undefined ? stats.poses : seq;
      wrap.dataset.posesReceived = String(stats.poses);
      pending = true;
      viewer.set_dirty();
    },
    height(h) {
      wrap.style.height = `${h}px`;
      viewer.set_3d_pane_size();
    },
    dispose() {
      if (!alive) return;
      alive = false;
      cancelAnimationFrame(frame);
      resize.disconnect();
      try {
        viewer.scene_tree.dispose_recursive();
      } catch (e) {
        // a half-built scene: nothing more to free
      }
      if (viewer.gui) viewer.gui.destroy();
      viewer.renderer.dispose();
      viewer.renderer.forceContextLoss();
      wrap.remove();
    },
  };
  wrap.kinlibScene = controller;
  return controller;
}

function kinlibDecode64(text) {
  const raw = atob(text);
  const out = new Uint8Array(raw.length);
  for (let i = 0; i < raw.length; i++) out[i] = raw.charCodeAt(i);
  return out;
}

function kinlibStaticScenes(MeshCat, root) {
  // Every <div class="kl-scene-static"> under `root` holding a <script
  // type="application/json"> of a saved scene (base64 commands and poses) becomes a viewer.
  const made = [];
  for (const holder of (root || document).querySelectorAll(".kl-scene-static")) {
    if (holder.kinlibScene) continue;
    const data = JSON.parse(holder.querySelector("script[type='application/json']").textContent);
    const ctl = kinlibMountScene(MeshCat, holder, data.height);
    ctl.commands(data.commands.map(kinlibDecode64));
    ctl.poses(data.paths, kinlibFloats(kinlibDecode64(data.poses)), 0);
    holder.kinlibScene = ctl;
    made.push(ctl);
  }
  return made;
}
