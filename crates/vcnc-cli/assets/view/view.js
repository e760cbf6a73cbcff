// vcnc view: a small hand-written WebGL 1 renderer for the scene `vcnc view` puts in the page
// (the tool's moves with their times, the tools' colours, the program texts, the simulated stock
// and the alarms). Lines for the toolpath, one shaded mesh for the stock, an orthographic
// orbit/pan/zoom camera; picking is done on the CPU against the projected segments, so it needs
// no second render pass and works the same without WebGL. `window.vcncView` is the test hook.
(function () {
  'use strict';

  const data = JSON.parse(document.getElementById('vcnc-data').textContent);
  const segments = data.segments;
  const count = segments.length;
  const canvas = document.getElementById('canvas');
  const $ = (id) => document.getElementById(id);

  // ---- The scene's geometry (part coordinates, mm) ----

  // Segment fields, as scene.rs writes them.
  const KIND = 0, SLOT = 1, FILE = 2, LINE = 3, T = 4, DT = 5, FROM = 6, TO = 9, CENTER = 12, AXES = 15, SWEEP = 17;
  const vec = (s, at) => [s[at], s[at + 1], s[at + 2]];

  // The point of segment `s` at fraction `f` of it: along the line, or around the arc (a helix
  // moves its normal axis evenly with the angle).
  function pointAt(s, f) {
    const from = vec(s, FROM), to = vec(s, TO);
    if (f >= 1) return to;
    if (s[KIND] !== 2) return from.map((v, i) => v + f * (to[i] - v));
    const c = vec(s, CENTER), a = s[AXES], b = s[AXES + 1], n = 3 - a - b;
    const r = Math.hypot(from[a] - c[a], from[b] - c[b]);
    const angle = Math.atan2(from[b] - c[b], from[a] - c[a]) + f * s[SWEEP];
    const p = [0, 0, 0];
    p[a] = c[a] + r * Math.cos(angle);
    p[b] = c[b] + r * Math.sin(angle);
    p[n] = from[n] + f * (to[n] - from[n]);
    return p;
  }

  // Arcs as chords of at most 5 degrees (and at most 120 of them).
  function chordsOf(s) {
    if (s[KIND] !== 2) return 1;
    return Math.min(120, Math.max(2, Math.ceil(Math.abs(s[SWEEP]) / (Math.PI / 36))));
  }

  // Every segment's polyline, flattened: `points[first[i] .. first[i + 1])` are segment i's.
  const first = new Uint32Array(count + 1);
  let pointCount = 0;
  for (let i = 0; i < count; i++) { first[i] = pointCount; pointCount += chordsOf(segments[i]) + 1; }
  first[count] = pointCount;
  const points = new Float64Array(pointCount * 3);
  // The extents of everything, and of the part (the cuts and the stock): the view fits the
  // part, since rapids to and from the machine's home would make it small.
  const box = () => ({ low: [Infinity, Infinity, Infinity], high: [-Infinity, -Infinity, -Infinity] });
  const whole = box(), part = box();
  function widen(b, p) { for (let k = 0; k < 3; k++) { b.low[k] = Math.min(b.low[k], p[k]); b.high[k] = Math.max(b.high[k], p[k]); } }
  for (let i = 0; i < count; i++) {
    const s = segments[i], chords = chordsOf(s);
    for (let k = 0; k <= chords; k++) {
      const p = pointAt(s, k / chords);
      points.set(p, (first[i] + k) * 3);
      widen(whole, p);
      if (s[KIND] !== 0) widen(part, p);
    }
  }
  const stock = data.stock;
  if (stock) {
    for (const p of [[stock.origin[0], stock.origin[1], stock.bottom],
      [stock.origin[0] + stock.cell[0] * stock.size[0], stock.origin[1] + stock.cell[1] * stock.size[1], stock.top]]) {
      widen(whole, p); widen(part, p);
    }
  }
  if (!isFinite(whole.low[0])) { whole.low.fill(0); whole.high.fill(1); }
  const framed = isFinite(part.low[0]) ? part : whole;
  const middle = (b) => b.low.map((v, k) => (v + b.high[k]) / 2);
  const halfDiagonal = (b) => Math.max(1, Math.hypot(...b.low.map((v, k) => b.high[k] - v)) / 2);
  // Everything is drawn relative to the centre: float32 keeps its precision near the part.
  const centre = middle(whole);
  const radius = halfDiagonal(whole);
  const endTime = count ? segments[count - 1][T] + segments[count - 1][DT] : 0;

  // ---- The camera: orthographic, orbiting its target ----

  const camera = { yaw: -Math.PI / 3, pitch: Math.PI / 5, scale: 1, target: [0, 0, 0] };
  function fit() {
    camera.target = middle(framed).map((v, k) => v - centre[k]);
    camera.scale = 0.9 * Math.min(canvas.clientWidth, canvas.clientHeight) / (2 * halfDiagonal(framed));
    draw();
  }
  // The camera's axes: right, up and towards the eye, in part directions.
  function basis() {
    const { yaw, pitch } = camera;
    const d = [Math.cos(pitch) * Math.cos(yaw), Math.cos(pitch) * Math.sin(yaw), Math.sin(pitch)];
    const r = [-Math.sin(yaw), Math.cos(yaw), 0];
    const u = [d[1] * r[2] - d[2] * r[1], d[2] * r[0] - d[0] * r[2], d[0] * r[1] - d[1] * r[0]];
    return { r, u, d };
  }
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  // Part point (relative to the centre) to clip space, as the vertex shaders do.
  function matrix() {
    const { r, u, d } = basis();
    const sx = 2 * camera.scale / canvas.clientWidth, sy = 2 * camera.scale / canvas.clientHeight;
    const depth = 1 / (2.5 * radius), t = camera.target;
    return new Float32Array([
      r[0] * sx, u[0] * sy, -d[0] * depth, 0,
      r[1] * sx, u[1] * sy, -d[1] * depth, 0,
      r[2] * sx, u[2] * sy, -d[2] * depth, 0,
      -dot(t, r) * sx, -dot(t, u) * sy, dot(t, d) * depth, 1,
    ]);
  }
  // A part point to CSS pixels of the viewport.
  function toScreen(p, m, rect) {
    const q = [p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]];
    const x = m[0] * q[0] + m[4] * q[1] + m[8] * q[2] + m[12];
    const y = m[1] * q[0] + m[5] * q[1] + m[9] * q[2] + m[13];
    return [rect.left + (x + 1) / 2 * rect.width, rect.top + (1 - y) / 2 * rect.height];
  }

  // ---- WebGL ----

  const gl = canvas.getContext('webgl', { antialias: true, preserveDrawingBuffer: true });
  const lineProgram = gl && program(
    'attribute vec3 aPos; attribute vec3 aColour; attribute float aDash; attribute float aTime;' +
    'uniform mat4 uMatrix; uniform vec3 uOffset;' +
    'varying vec3 vColour; varying float vDash; varying float vTime;' +
    'void main() { gl_Position = uMatrix * vec4(aPos + uOffset, 1.0); vColour = aColour; vDash = aDash; vTime = aTime; }',
    'precision highp float; uniform float uTime; uniform float uDash; uniform float uRapids;' +
    'varying vec3 vColour; varying float vDash; varying float vTime;' +
    'void main() {' +
    '  if (vDash >= 0.0 && (uRapids < 0.5 || mod(vDash, 2.0 * uDash) > uDash)) discard;' +
    '  gl_FragColor = vec4(vTime > uTime ? mix(vec3(1.0), vColour, 0.3) : vColour, 1.0);' +
    '}');
  const meshProgram = gl && program(
    'attribute vec3 aPos; attribute vec3 aNormal; uniform mat4 uMatrix; varying vec3 vNormal;' +
    'void main() { gl_Position = uMatrix * vec4(aPos, 1.0); vNormal = aNormal; }',
    'precision mediump float; varying vec3 vNormal;' +
    'void main() { float light = max(dot(normalize(vNormal), normalize(vec3(0.4, -0.5, 1.0))), 0.0);' +
    '  gl_FragColor = vec4(vec3(0.70, 0.73, 0.78) * (0.45 + 0.55 * light), 1.0); }');

  function program(vertexSource, fragmentSource) {
    const p = gl.createProgram();
    for (const [type, source] of [[gl.VERTEX_SHADER, vertexSource], [gl.FRAGMENT_SHADER, fragmentSource]]) {
      const shader = gl.createShader(type);
      gl.shaderSource(shader, source);
      gl.compileShader(shader);
      if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(shader));
      gl.attachShader(p, shader);
    }
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(p));
    return p;
  }

  // A buffer of line vertices: position (3), colour (3), dash distance (-1: solid) and time.
  const LINE_FLOATS = 8;
  function lineBuffer(vertices) {
    if (!gl) return null;
    const buffer = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(vertices), gl.STATIC_DRAW);
    return { buffer, vertices: vertices.length / LINE_FLOATS };
  }
  function pushLine(out, a, b, colour, dashFrom, dashTo, time) {
    out.push(a[0] - centre[0], a[1] - centre[1], a[2] - centre[2], ...colour, dashFrom, time);
    out.push(b[0] - centre[0], b[1] - centre[1], b[2] - centre[2], ...colour, dashTo, time);
  }
  const unit = (rgb) => rgb.map((c) => c / 255);
  const rapidColour = unit(data.rapid_colour);
  const toolColour = (slot) => unit(data.tools[slot] ? data.tools[slot].colour : [0, 0, 0]);

  // `timed`: drawn faded while the slider is before the segment (the highlight never is).
  function toolpathVertices(indices, colourOf, timed) {
    const out = [];
    for (const i of indices) {
      const s = segments[i], rapid = s[KIND] === 0;
      const colour = colourOf(s);
      let along = 0;
      for (let k = first[i]; k + 1 < first[i + 1]; k++) {
        const a = points.subarray(k * 3, k * 3 + 3), b = points.subarray(k * 3 + 3, k * 3 + 6);
        const length = Math.hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
        pushLine(out, a, b, colour, rapid ? along : -1, rapid ? along + length : -1, timed ? s[T] : -1);
        along += length;
      }
    }
    return out;
  }
  const all = Array.from({ length: count }, (_, i) => i);
  const toolpath = lineBuffer(toolpathVertices(all, (s) => (s[KIND] === 0 ? rapidColour : toolColour(s[SLOT])), true));
  let highlight = null;

  // Alarm markers: a small star of three lines, red for an error, orange for a warning.
  const markerVertices = [];
  for (const alarm of data.alarms) {
    if (!alarm.at) continue;
    const size = halfDiagonal(framed) / 25, colour = alarm.error ? [0.85, 0, 0] : [0.95, 0.55, 0];
    for (let k = 0; k < 3; k++) {
      const a = alarm.at.slice(), b = alarm.at.slice();
      a[k] -= size; b[k] += size;
      pushLine(markerVertices, a, b, colour, -1, -1, -1);
    }
  }
  const markers = lineBuffer(markerVertices);

  // The tool: a wire cylinder of its diameter and drawn length, its tip at the origin.
  function toolVertices(slot) {
    const tool = data.tools[slot] || { diameter: 1, length: 5 };
    const r = Math.max(tool.diameter / 2, halfDiagonal(framed) / 200), h = tool.length, out = [], colour = [0.1, 0.1, 0.1];
    const at = (k, z) => [centre[0] + r * Math.cos(k * Math.PI / 12), centre[1] + r * Math.sin(k * Math.PI / 12), centre[2] + z];
    for (let k = 0; k < 24; k++) {
      pushLine(out, at(k, 0), at(k + 1, 0), colour, -1, -1, -1);
      pushLine(out, at(k, h), at(k + 1, h), colour, -1, -1, -1);
      if (k % 3 === 0) pushLine(out, at(k, 0), at(k, h), colour, -1, -1, -1);
    }
    return out;
  }
  const toolShapes = data.tools.map((_, slot) => lineBuffer(toolVertices(slot)));

  // The stock: the height field through its cell centres, with walls down to its bottom.
  const stockMesh = gl && stock && meshBuffer(stockTriangles());
  function stockTriangles() {
    const [nx, ny] = stock.size, out = [];
    const x = (i) => stock.origin[0] + (i + 0.5) * stock.cell[0] - centre[0];
    const y = (j) => stock.origin[1] + (j + 0.5) * stock.cell[1] - centre[1];
    const z = (i, j) => stock.heights[j * nx + i] - centre[2];
    const bottom = stock.bottom - centre[2];
    const triangle = (a, b, c) => {
      const u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]], v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
      const n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
      for (const p of [a, b, c]) out.push(...p, ...n);
    };
    const quad = (a, b, c, d) => { triangle(a, b, c); triangle(a, c, d); };
    for (let j = 0; j + 1 < ny; j++) {
      for (let i = 0; i + 1 < nx; i++) {
        quad([x(i), y(j), z(i, j)], [x(i + 1), y(j), z(i + 1, j)], [x(i + 1), y(j + 1), z(i + 1, j + 1)], [x(i), y(j + 1), z(i, j + 1)]);
      }
    }
    for (let i = 0; i + 1 < nx; i++) {
      quad([x(i), y(0), bottom], [x(i + 1), y(0), bottom], [x(i + 1), y(0), z(i + 1, 0)], [x(i), y(0), z(i, 0)]);
      const j = ny - 1;
      quad([x(i + 1), y(j), bottom], [x(i), y(j), bottom], [x(i), y(j), z(i, j)], [x(i + 1), y(j), z(i + 1, j)]);
    }
    for (let j = 0; j + 1 < ny; j++) {
      const i = nx - 1;
      quad([x(i), y(j), bottom], [x(i), y(j + 1), bottom], [x(i), y(j + 1), z(i, j + 1)], [x(i), y(j), z(i, j)]);
      quad([x(0), y(j + 1), bottom], [x(0), y(j), bottom], [x(0), y(j), z(0, j)], [x(0), y(j + 1), z(0, j + 1)]);
    }
    return out;
  }
  function meshBuffer(vertices) {
    const buffer = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(vertices), gl.STATIC_DRAW);
    return { buffer, vertices: vertices.length / 6 };
  }

  // ---- Drawing ----

  // A stock nothing cut (no tool with a radius) would only hide the path: it starts hidden.
  const uncut = !!stock && stock.heights.every((h) => h >= stock.top - 1e-6);
  const state = { time: endTime, selected: -1, tool: [0, 0, 0], slot: 0, showStock: !uncut, showRapids: true };
  let pending = false;
  function draw() {
    if (!gl || pending) return;
    pending = true;
    requestAnimationFrame(render);
  }
  function render() {
    pending = false;
    const ratio = window.devicePixelRatio || 1;
    const width = Math.round(canvas.clientWidth * ratio), height = Math.round(canvas.clientHeight * ratio);
    if (canvas.width !== width || canvas.height !== height) { canvas.width = width; canvas.height = height; }
    gl.viewport(0, 0, width, height);
    gl.clearColor(0.98, 0.98, 0.98, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    const m = matrix();
    if (stockMesh && state.showStock) {
      gl.useProgram(meshProgram);
      gl.uniformMatrix4fv(gl.getUniformLocation(meshProgram, 'uMatrix'), false, m);
      // Pushed back a little: the cut's lines lie on the surface they cut.
      gl.enable(gl.POLYGON_OFFSET_FILL);
      gl.polygonOffset(1, 2);
      gl.bindBuffer(gl.ARRAY_BUFFER, stockMesh.buffer);
      attribute(meshProgram, 'aPos', 3, 6, 0);
      attribute(meshProgram, 'aNormal', 3, 6, 3);
      gl.drawArrays(gl.TRIANGLES, 0, stockMesh.vertices);
      gl.disable(gl.POLYGON_OFFSET_FILL);
    }
    gl.useProgram(lineProgram);
    gl.uniformMatrix4fv(gl.getUniformLocation(lineProgram, 'uMatrix'), false, m);
    gl.uniform1f(gl.getUniformLocation(lineProgram, 'uTime'), state.time);
    gl.uniform1f(gl.getUniformLocation(lineProgram, 'uDash'), 4 / camera.scale);
    gl.uniform1f(gl.getUniformLocation(lineProgram, 'uRapids'), state.showRapids ? 1 : 0);
    lines(toolpath, [0, 0, 0]);
    gl.disable(gl.DEPTH_TEST);
    if (highlight) lines(highlight, [0, 0, 0]);
    lines(markers, [0, 0, 0]);
    if (toolShapes[state.slot]) lines(toolShapes[state.slot], state.tool.map((v, k) => v - centre[k]));
  }
  function lines(b, offset) {
    if (!b || !b.vertices) return;
    gl.uniform3fv(gl.getUniformLocation(lineProgram, 'uOffset'), offset);
    gl.bindBuffer(gl.ARRAY_BUFFER, b.buffer);
    attribute(lineProgram, 'aPos', 3, LINE_FLOATS, 0);
    attribute(lineProgram, 'aColour', 3, LINE_FLOATS, 3);
    attribute(lineProgram, 'aDash', 1, LINE_FLOATS, 6);
    attribute(lineProgram, 'aTime', 1, LINE_FLOATS, 7);
    gl.drawArrays(gl.LINES, 0, b.vertices);
  }
  function attribute(p, name, size, stride, offset) {
    const at = gl.getAttribLocation(p, name);
    if (at < 0) return;
    gl.enableVertexAttribArray(at);
    gl.vertexAttribPointer(at, size, gl.FLOAT, false, stride * 4, offset * 4);
  }

  // ---- The timeline ----

  // The segment the tool is on at `time`: the last one starting at or before it.
  function segmentAtTime(time) {
    let lo = 0, hi = count - 1;
    if (hi < 0) return -1;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (segments[mid][T] <= time) lo = mid; else hi = mid - 1;
    }
    return lo;
  }
  // Where the tool is at `time`: inside its segment at the fraction of the segment's duration
  // gone (an even speed along the segment: the trace gives each segment's start and duration only).
  function setTime(time) {
    state.time = Math.max(0, Math.min(endTime, Number(time)));
    const i = segmentAtTime(state.time);
    if (i >= 0) {
      const s = segments[i];
      const f = s[DT] > 0 ? Math.max(0, Math.min(1, (state.time - s[T]) / s[DT])) : 1;
      state.tool = pointAt(s, state.time < s[T] ? 0 : f);
      state.slot = s[SLOT];
    }
    $('slider').value = String(state.time);
    $('time').textContent = `${state.time.toFixed(3)} s / ${endTime.toFixed(3)} s` + (i >= 0 ? `  line ${segments[i][LINE]}` : '');
    draw();
  }

  // ---- Picking and the program panel ----

  // The segment nearest to the viewport point (x, y) within 6 pixels, or -1.
  function pick(x, y) {
    const m = matrix(), rect = canvas.getBoundingClientRect();
    let best = -1, bestDistance = 6;
    for (let i = 0; i < count; i++) {
      if (!state.showRapids && segments[i][KIND] === 0) continue;
      let a = toScreen(points.subarray(first[i] * 3, first[i] * 3 + 3), m, rect);
      for (let k = first[i] + 1; k < first[i + 1]; k++) {
        const b = toScreen(points.subarray(k * 3, k * 3 + 3), m, rect);
        const distance = toSegment(x, y, a, b);
        if (distance < bestDistance) { bestDistance = distance; best = i; }
        a = b;
      }
    }
    return best;
  }
  function toSegment(x, y, a, b) {
    const dx = b[0] - a[0], dy = b[1] - a[1], length2 = dx * dx + dy * dy;
    const f = length2 > 0 ? Math.max(0, Math.min(1, ((x - a[0]) * dx + (y - a[1]) * dy) / length2)) : 0;
    return Math.hypot(x - a[0] - f * dx, y - a[1] - f * dy);
  }

  let shownFile = -1;
  function showLine(file, line) {
    const panel = $('program');
    if (file !== shownFile && data.files[file]) {
      shownFile = file;
      panel.textContent = '';
      const fragment = document.createDocumentFragment();
      data.files[file].lines.forEach((text, k) => {
        const row = document.createElement('div');
        const number = document.createElement('span');
        number.className = 'no';
        number.textContent = String(k + 1);
        row.append(number, text);
        fragment.append(row);
      });
      panel.append(fragment);
    }
    for (const row of panel.querySelectorAll('div.current')) row.classList.remove('current');
    const row = panel.children[line - 1];
    if (row) { row.classList.add('current'); row.scrollIntoView({ block: 'center' }); }
  }
  function select(i) {
    state.selected = i;
    if (highlight) gl.deleteBuffer(highlight.buffer);
    const info = $('info');
    if (i < 0) {
      info.textContent = 'Click a segment to see its block.';
      highlight = null;
      draw();
      return;
    }
    const s = segments[i], file = data.files[s[FILE]];
    const kind = ['rapid', 'feed', 'arc'][s[KIND]];
    const tool = data.tools[s[SLOT]];
    info.textContent = '';
    const place = document.createElement('div');
    place.textContent = `${file ? file.name : '?'}:${s[LINE]}  segment ${i + 1} of ${count}, ${kind}` +
      (tool ? `, T${tool.number}` : '') + `, t ${s[T].toFixed(3)} s + ${s[DT].toFixed(3)} s`;
    const block = document.createElement('div');
    block.className = 'block';
    block.textContent = file ? (file.lines[s[LINE] - 1] || '') : '';
    info.append(place, block);
    highlight = lineBuffer(toolpathVertices([i], () => [0, 0, 0], false));
    showLine(s[FILE], s[LINE]);
    draw();
  }

  // ---- Panels and input ----

  const legend = $('legend');
  for (const tool of data.tools) {
    const row = document.createElement('div');
    const swatch = document.createElement('span');
    swatch.className = 'swatch';
    swatch.style.background = `rgb(${tool.colour.join(',')})`;
    row.append(swatch, `T${tool.number}  \u2300${tool.diameter}`);
    legend.append(row);
  }
  const rapidRow = document.createElement('div');
  rapidRow.innerHTML = '<span class="swatch" style="background:repeating-linear-gradient(90deg,#969696 0 4px,transparent 4px 8px)"></span>rapid';
  legend.append(rapidRow);
  document.title = `vcnc view: ${data.name}`;

  const alarmList = $('alarms');
  if (!data.alarms.length) alarmList.style.display = 'none';
  for (const alarm of data.alarms) {
    const row = document.createElement('div');
    row.className = alarm.error ? 'error' : 'warning';
    row.textContent = `${alarm.code} ${alarm.name || ''}:${alarm.line || ''} ${alarm.message}`;
    row.addEventListener('click', () => {
      if (alarm.segment !== null) select(alarm.segment);
      else if (alarm.file !== null) showLine(alarm.file, alarm.line);
    });
    alarmList.append(row);
  }
  if (data.files.length) showLine(0, 1);

  const slider = $('slider');
  slider.max = String(endTime);
  slider.addEventListener('input', () => setTime(slider.value));
  let playing = null;
  $('play').addEventListener('click', () => {
    if (playing) { cancelAnimationFrame(playing); playing = null; $('play').textContent = 'Play'; return; }
    // The whole program in about 30 seconds, never slower than the machine.
    const speed = Math.max(1, endTime / 30);
    let last = performance.now();
    if (state.time >= endTime) setTime(0);
    $('play').textContent = 'Pause';
    const step = (now) => {
      setTime(state.time + (now - last) / 1000 * speed);
      last = now;
      if (state.time < endTime) playing = requestAnimationFrame(step);
      else { playing = null; $('play').textContent = 'Play'; }
    };
    playing = requestAnimationFrame(step);
  });
  $('show-stock').disabled = !stock;
  $('show-stock').checked = !!stock && state.showStock;
  $('show-stock').addEventListener('change', (e) => { state.showStock = e.target.checked; draw(); });
  $('show-rapids').addEventListener('change', (e) => { state.showRapids = e.target.checked; draw(); });
  $('reset').addEventListener('click', fit);

  let drag = null;
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('mousedown', (e) => {
    drag = { x: e.clientX, y: e.clientY, pan: e.shiftKey || e.button !== 0, moved: false };
  });
  window.addEventListener('mousemove', (e) => {
    if (!drag) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    if (Math.abs(dx) + Math.abs(dy) > 3) drag.moved = true;
    if (!drag.moved) return;
    drag.x = e.clientX; drag.y = e.clientY;
    if (drag.pan) {
      const { r, u } = basis();
      camera.target = camera.target.map((v, k) => v - (r[k] * dx - u[k] * dy) / camera.scale);
    } else {
      camera.yaw -= dx * 0.01;
      camera.pitch = Math.max(-1.55, Math.min(1.55, camera.pitch + dy * 0.01));
    }
    draw();
  });
  window.addEventListener('mouseup', (e) => {
    if (drag && !drag.moved && e.button === 0) select(pick(e.clientX, e.clientY));
    drag = null;
  });
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    // Zoom about the cursor: the point under it stays there.
    const rect = canvas.getBoundingClientRect();
    const px = e.clientX - rect.left - rect.width / 2, py = rect.height / 2 - (e.clientY - rect.top);
    const before = camera.scale;
    camera.scale *= Math.exp(-e.deltaY * 0.0015);
    const { r, u } = basis(), shift = 1 / before - 1 / camera.scale;
    camera.target = camera.target.map((v, k) => v + (r[k] * px + u[k] * py) * shift);
    draw();
  }, { passive: false });
  window.addEventListener('resize', draw);

  // ---- The test hook ----

  window.vcncView = {
    // How many segments the page holds (one per motion record of `vcnc trace`).
    segmentCount: () => count,
    // Segment i's middle in viewport CSS pixels, where a click selects it.
    project: (i) => toScreen(pointAt(segments[i], 0.5), matrix(), canvas.getBoundingClientRect()),
    // Segment i as the page holds it: line, time, duration.
    segment: (i) => ({ line: segments[i][LINE], file: segments[i][FILE], t: segments[i][T], dt: segments[i][DT] }),
    setTime,
    // The tool's tip, part coordinates, mm.
    toolPosition: () => state.tool.slice(),
    selected: () => state.selected,
    webgl: !!gl,
  };

  // `#t=SECONDS&segment=N` (N counted from 1) opens the page at that time with that segment
  // selected: a view to link to or to take a picture of.
  const asked = new URLSearchParams(location.hash.slice(1));
  fit();
  setTime(asked.has('t') ? Number(asked.get('t')) || 0 : endTime);
  const chosen = Number(asked.get('segment'));
  if (Number.isInteger(chosen) && chosen >= 1 && chosen <= count) select(chosen - 1);
})();
