// The ARS replay player: a small WebGL renderer of the replay's shapes (Lambert
// shading as ARS's fast off-screen renderer draws them, checkered floors), an orbit
// camera that starts where the program's camera is, play/pause, a time slider, speed
// and plots of sensor columns. No library, no network. The shapes come as triangles
// with normals, made by ARS in Rust: nothing is tessellated here.
//
// Page API, for tests and embedding: window.arsReplay = { ready, error, start, end,
// duration, frames, time, playing, speed, seek(t), play(), pause(), setSpeed(s),
// render() }. Times are simulated seconds. The URL hash sets the start:
// #t=2 shows t = 2 s, paused; #until=2 plays from the start and stops at t = 2 s.
"use strict";
(function () {
  const api = {
    ready: false, error: null, start: 0, end: 0, duration: 0, frames: 0, time: 0,
    playing: false, speed: 1, until: null,
  };
  window.arsReplay = api;
  const $ = (id) => document.getElementById(id);

  // ---- Data -------------------------------------------------------------------
  async function inflate(text) {
    const binary = atob(text.trim());
    const bytes = new Uint8Array(binary.length);
    for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
    const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("deflate"));
    return await new Response(stream).arrayBuffer();
  }

  function unpack(buffer) {
    const length = new DataView(buffer).getUint32(0, true);
    const header = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 4, length)));
    const base = 4 + length;
    const types = { f32: Float32Array, u32: Uint32Array, u16: Uint16Array, i8: Int8Array };
    const array = (r) => new types[r.type](buffer, base + r.offset, r.count);
    return { header, array };
  }

  // ---- Matrices (column-major, as WebGL wants them) -----------------------------
  function multiply(a, b) {
    const out = new Float32Array(16);
    for (let c = 0; c < 4; c++)
      for (let r = 0; r < 4; r++) {
        let s = 0;
        for (let k = 0; k < 4; k++) s += a[k * 4 + r] * b[c * 4 + k];
        out[c * 4 + r] = s;
      }
    return out;
  }
  function perspective(fovY, aspect, near, far) {
    const f = 1 / Math.tan(fovY / 2), m = new Float32Array(16);
    m[0] = f / aspect; m[5] = f; m[10] = (far + near) / (near - far); m[11] = -1;
    m[14] = (2 * far * near) / (near - far);
    return m;
  }
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const norm = (a) => { const l = Math.hypot(a[0], a[1], a[2]) || 1; return [a[0] / l, a[1] / l, a[2] / l]; };
  function lookAt(eye, at, up) {
    const z = norm(sub(eye, at)), x = norm(cross(up, z)), y = cross(z, x);
    return new Float32Array([x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0,
      -dot(x, eye), -dot(y, eye), -dot(z, eye), 1]);
  }
  // A pose [x, y, z, qx, qy, qz, qw] as a matrix.
  function poseMatrix(p, o) {
    o = o || 0;
    const [x, y, z, qx, qy, qz, qw] = [p[o], p[o + 1], p[o + 2], p[o + 3], p[o + 4], p[o + 5], p[o + 6]];
    return new Float32Array([
      1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy + qz * qw), 2 * (qx * qz - qy * qw), 0,
      2 * (qx * qy - qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz + qx * qw), 0,
      2 * (qx * qz + qy * qw), 2 * (qy * qz - qx * qw), 1 - 2 * (qx * qx + qy * qy), 0,
      x, y, z, 1]);
  }
  // Between two poses: positions linearly, rotations by normalised lerp (shortest way).
  function blend(p, a, b, s, out) {
    for (let i = 0; i < 3; i++) out[i] = p[a + i] * (1 - s) + p[b + i] * s;
    const sign = p[a + 3] * p[b + 3] + p[a + 4] * p[b + 4] + p[a + 5] * p[b + 5] + p[a + 6] * p[b + 6] < 0 ? -1 : 1;
    let l = 0;
    for (let i = 3; i < 7; i++) { out[i] = p[a + i] * (1 - s) + sign * p[b + i] * s; l += out[i] * out[i]; }
    l = Math.sqrt(l) || 1;
    for (let i = 3; i < 7; i++) out[i] /= l;
    return out;
  }

  // ---- WebGL ---------------------------------------------------------------------
  const VERTEX = `
    attribute vec3 position; attribute vec3 normal;
    uniform mat4 model; uniform mat4 viewProjection;
    varying vec3 world; varying vec3 worldNormal;
    void main() {
      vec4 w = model * vec4(position, 1.0);
      world = w.xyz; worldNormal = (model * vec4(normal, 0.0)).xyz;
      gl_Position = viewProjection * w;
    }`;
  // ARS's fast material (flat.wgsl): a headlight and a key light from above, a little
  // highlight, an optional checker (floors, 1 m cells).
  const FRAGMENT = `
    precision mediump float;
    uniform vec3 color; uniform vec3 eye; uniform vec3 key; uniform float checker;
    varying vec3 world; varying vec3 worldNormal;
    void main() {
      vec3 n = normalize(worldNormal);
      if (!gl_FrontFacing) n = -n;
      vec3 toEye = normalize(eye - world);
      float head = max(dot(n, toEye), 0.0), k = max(dot(n, key), 0.0);
      vec3 base = color;
      if (checker > 0.5) {
        float cell = floor(world.x) + floor(world.z);
        if (cell - 2.0 * floor(cell / 2.0) > 0.5) base *= 0.82;
      }
      float shine = pow(max(dot(n, normalize(toEye + key)), 0.0), 48.0) * 0.15;
      vec3 lit = base * (0.30 + 0.45 * head + 0.35 * k) + vec3(shine);
      // The off-screen renderer's pixels are about this shading to the power 0.51
      // (measured on the same scenes: kiss3d's colour handling): so are these.
      gl_FragColor = vec4(pow(clamp(lit, 0.0, 1.0), vec3(0.51)), 1.0);
    }`;

  function compile(gl) {
    const shader = (type, source) => {
      const s = gl.createShader(type);
      gl.shaderSource(s, source);
      gl.compileShader(s);
      if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
      return s;
    };
    const program = gl.createProgram();
    gl.attachShader(program, shader(gl.VERTEX_SHADER, VERTEX));
    gl.attachShader(program, shader(gl.FRAGMENT_SHADER, FRAGMENT));
    gl.linkProgram(program);
    if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(program));
    const u = (name) => gl.getUniformLocation(program, name);
    return {
      program, position: gl.getAttribLocation(program, "position"), normal: gl.getAttribLocation(program, "normal"),
      model: u("model"), viewProjection: u("viewProjection"), color: u("color"), eye: u("eye"), key: u("key"),
      checker: u("checker"),
    };
  }

  // A mesh as Rust sent it (positions, normals as normalized bytes, three indices a
  // triangle), into buffers once.
  function upload(gl, mesh, array) {
    const buffer = (target, values) => {
      const b = gl.createBuffer();
      gl.bindBuffer(target, b);
      gl.bufferData(target, values, gl.STATIC_DRAW);
      return b;
    };
    const indices = array(mesh.indices), wide = indices instanceof Uint32Array;
    // Each index came as its difference from the one before: summed back (wrapping as
    // the array's type does, as Rust's differences did).
    for (let i = 1; i < indices.length; i++) indices[i] += indices[i - 1];
    if (wide && !gl.getExtension("OES_element_index_uint"))
      throw new Error("this browser's WebGL cannot draw a mesh of more than 65536 vertices");
    return {
      positions: buffer(gl.ARRAY_BUFFER, array(mesh.positions)),
      normals: buffer(gl.ARRAY_BUFFER, array(mesh.normals)),
      indices: buffer(gl.ELEMENT_ARRAY_BUFFER, indices),
      count: indices.length,
      type: wide ? gl.UNSIGNED_INT : gl.UNSIGNED_SHORT,
    };
  }

  // ---- The player ----------------------------------------------------------------
  async function main() {
    const { header, array } = unpack(await inflate($("ars-data").textContent));
    const view = header.view, times = array(header.times), poses = array(header.poses);
    const tracks = header.tracks, frames = times.length;
    Object.assign(api, { start: times[0], end: times[frames - 1], frames });
    api.duration = api.end - api.start;
    api.time = api.start;

    const canvas = $("ars-view");
    [canvas.width, canvas.height] = view.size;
    canvas.style.width = view.size[0] + "px";
    canvas.style.height = view.size[1] + "px";
    const controlsWidth = view.size[0] + "px";
    $("ars-controls").style.width = controlsWidth;
    const gl = canvas.getContext("webgl", { antialias: true, preserveDrawingBuffer: true });
    if (!gl) throw new Error("this browser has no WebGL: the replay cannot be drawn");
    const shader = compile(gl);
    gl.enable(gl.DEPTH_TEST);
    const bg = view.background;

    // Every mesh uploaded once; parts of the same shape share theirs.
    const meshes = header.meshes.map((m) => upload(gl, m, array));
    const objects = header.objects.map((o) => ({
      floor: o.floor, pose: o.pose, track: o.track,
      parts: o.parts.map((p) => ({ local: poseMatrix(p.pose), color: p.color, mesh: meshes[p.mesh] })),
    }));

    // The orbit camera: yaw and pitch about the target, as kiss3d's.
    const camera = { target: view.target.slice(), distance: 1, yaw: 0, pitch: 0 };
    {
      const d = sub(view.eye, view.target);
      camera.distance = Math.hypot(d[0], d[1], d[2]);
      camera.yaw = Math.atan2(d[2], d[0]);
      camera.pitch = Math.acos(Math.max(-1, Math.min(1, d[1] / camera.distance)));
    }
    const eyeOf = () => [
      camera.target[0] + camera.distance * Math.sin(camera.pitch) * Math.cos(camera.yaw),
      camera.target[1] + camera.distance * Math.cos(camera.pitch),
      camera.target[2] + camera.distance * Math.sin(camera.pitch) * Math.sin(camera.yaw),
    ];
    const key = norm([0.3, 1.0, 0.45]);
    const pose = new Float32Array(7);

    function render() {
      gl.viewport(0, 0, canvas.width, canvas.height);
      gl.clearColor(bg[0], bg[1], bg[2], 1);
      gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
      gl.useProgram(shader.program);
      const eye = eyeOf();
      const vp = multiply(perspective(view.fov_y, canvas.width / canvas.height, view.near, view.far),
        lookAt(eye, camera.target, view.up));
      gl.uniformMatrix4fv(shader.viewProjection, false, vp);
      gl.uniform3fv(shader.eye, eye);
      gl.uniform3fv(shader.key, key);
      // The samples around the time shown, and how far between them.
      let hi = 0;
      while (hi < frames - 1 && times[hi] < api.time) hi++;
      const lo = Math.max(0, hi - 1);
      const span = times[hi] - times[lo];
      const s = span > 0 ? Math.min(1, Math.max(0, (api.time - times[lo]) / span)) : 1;
      for (const o of objects) {
        let at = o.pose;
        if (o.track !== null) {
          const stride = tracks * 7;
          at = blend(poses, lo * stride + o.track * 7, hi * stride + o.track * 7, s, pose);
          if (!Number.isFinite(at[0])) continue; // gone
        }
        const objectMatrix = poseMatrix(at);
        gl.uniform1f(shader.checker, o.floor ? 1 : 0);
        for (const p of o.parts) {
          gl.uniformMatrix4fv(shader.model, false, multiply(objectMatrix, p.local));
          gl.uniform3fv(shader.color, p.color);
          gl.bindBuffer(gl.ARRAY_BUFFER, p.mesh.positions);
          gl.enableVertexAttribArray(shader.position);
          gl.vertexAttribPointer(shader.position, 3, gl.FLOAT, false, 0, 0);
          gl.bindBuffer(gl.ARRAY_BUFFER, p.mesh.normals);
          gl.enableVertexAttribArray(shader.normal);
          gl.vertexAttribPointer(shader.normal, 3, gl.BYTE, true, 0, 0);
          gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, p.mesh.indices);
          gl.drawElements(gl.TRIANGLES, p.mesh.count, p.mesh.type, 0);
        }
      }
      drawPlots();
      $("ars-time").textContent = `t = ${api.time.toFixed(3)} s / ${api.end.toFixed(3)} s`;
      const slider = $("ars-slider");
      if (document.activeElement !== slider)
        slider.value = String(Math.round((1000 * (api.time - api.start)) / (api.duration || 1)));
      $("ars-play").textContent = api.playing ? "Pause" : "Play";
    }

    // Plots of sensor columns, with a cursor at the time shown.
    const plots = header.plots.map((p) => {
      const c = document.createElement("canvas");
      c.className = "ars-plot";
      c.width = view.size[0];
      c.height = 120;
      $("ars-plots").appendChild(c);
      const t = array(p.times), v = array(p.values);
      let min = Infinity, max = -Infinity;
      for (const x of v) { min = Math.min(min, x); max = Math.max(max, x); }
      if (!(max > min)) { min -= 1; max += 1; }
      return { label: p.label, canvas: c, t, v, min, max };
    });
    function drawPlots() {
      for (const p of plots) {
        const c = p.canvas.getContext("2d"), [w, h] = [p.canvas.width, p.canvas.height];
        const [left, right, top, bottom] = [52, 8, 18, 16];
        const x = (t) => left + ((t - api.start) / (api.duration || 1)) * (w - left - right);
        const y = (v) => top + (1 - (v - p.min) / (p.max - p.min)) * (h - top - bottom);
        c.clearRect(0, 0, w, h);
        c.fillStyle = "#222";
        c.font = "12px sans-serif";
        c.fillText(p.label, left, 13);
        c.fillText(p.max.toPrecision(4), 2, top + 4);
        c.fillText(p.min.toPrecision(4), 2, h - bottom);
        c.strokeStyle = "#ccc";
        c.strokeRect(left, top, w - left - right, h - top - bottom);
        c.strokeStyle = "#1f5fbf";
        c.beginPath();
        for (let i = 0; i < p.t.length; i++) (i ? c.lineTo : c.moveTo).call(c, x(p.t[i]), y(p.v[i]));
        c.stroke();
        c.strokeStyle = "#d22";
        c.beginPath();
        c.moveTo(x(api.time), top);
        c.lineTo(x(api.time), h - bottom);
        c.stroke();
      }
    }

    // Playing: simulated time advances with the page's clock times the speed, drawn
    // about 60 times a second. A timer rather than requestAnimationFrame: timers
    // follow a headless browser's virtual time, so a test can let it play.
    let last = null;
    function tick() {
      if (!api.playing) { last = null; return; }
      const now = performance.now();
      if (last !== null) {
        let t = api.time + ((now - last) / 1000) * api.speed;
        if (api.until !== null && t >= api.until) { t = api.until; api.playing = false; api.until = null; }
        if (t >= api.end) { t = api.end; api.playing = false; }
        api.time = t;
        render();
      }
      last = now;
      if (api.playing) setTimeout(tick, 16);
    }
    api.seek = (t) => { api.time = Math.min(api.end, Math.max(api.start, Number(t))); render(); };
    api.play = () => {
      if (api.playing) return;
      if (api.time >= api.end) api.time = api.start;
      api.playing = true;
      last = null;
      render();
      tick();
    };
    api.pause = () => { api.playing = false; render(); };
    api.setSpeed = (s) => { if (s > 0 && Number.isFinite(s)) { api.speed = Number(s); $("ars-speed").value = String(s); } };
    api.render = render;

    $("ars-play").onclick = () => (api.playing ? api.pause() : api.play());
    $("ars-slider").oninput = (e) => api.seek(api.start + (Number(e.target.value) / 1000) * api.duration);
    $("ars-speed").onchange = (e) => { api.speed = Number(e.target.value); };
    // Orbit with the left button, pan with the right one (or shift), zoom with the wheel.
    let drag = null;
    canvas.addEventListener("contextmenu", (e) => e.preventDefault());
    canvas.addEventListener("pointerdown", (e) => {
      drag = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey };
      canvas.setPointerCapture(e.pointerId);
    });
    canvas.addEventListener("pointerup", () => { drag = null; });
    canvas.addEventListener("pointermove", (e) => {
      if (!drag) return;
      const [dx, dy] = [e.clientX - drag.x, e.clientY - drag.y];
      drag.x = e.clientX;
      drag.y = e.clientY;
      if (drag.pan) {
        const eye = eyeOf(), forward = norm(sub(camera.target, eye));
        const right = norm(cross(forward, view.up)), up = cross(right, forward);
        const scale = (camera.distance * 2 * Math.tan(view.fov_y / 2)) / canvas.height;
        for (let i = 0; i < 3; i++) camera.target[i] += (-dx * right[i] + dy * up[i]) * scale;
      } else {
        camera.yaw += dx * 0.01;
        camera.pitch = Math.min(Math.PI - 0.01, Math.max(0.01, camera.pitch - dy * 0.01));
      }
      render();
    });
    canvas.addEventListener("wheel", (e) => {
      e.preventDefault();
      camera.distance = Math.max(0.01, camera.distance * Math.pow(1.0015, e.deltaY));
      render();
    }, { passive: false });

    // The start the URL asks for.
    const hash = new URLSearchParams(location.hash.slice(1));
    if (hash.has("t")) api.seek(Number(hash.get("t")));
    else render();
    if (hash.has("until")) {
      api.time = api.start;
      api.until = Math.min(api.end, Number(hash.get("until")));
      api.play();
    }
    api.ready = true;
  }

  main().catch((e) => {
    api.error = String(e && e.message ? e.message : e);
    $("ars-error").textContent = "The replay could not be shown: " + api.error;
  });
})();
