// Loads each case of cases.json through three.js's KTX2Loader, draws every mip level into a float render
// target (textureLod at the texel centres, nearest filtering, so each output pixel is one decoded texel),
// reads it back and compares it with the reference (heightpack's reader's decode, as unorm values) and,
// where the case names one, with a wrong reference (another format's decode of the same map), which the
// test requires to miss its bound; the report is posted to the test's server (POST /result).
import * as THREE from 'three';
import { KTX2Loader } from 'three/addons/loaders/KTX2Loader.js';

const messages = [];  // three's warnings and errors, as a loader or the renderer prints them
for (const kind of ['warn', 'error']) {
    const original = console[kind].bind(console);
    console[kind] = (...args) => { messages.push(args.map(String).join(' ')); original(...args); };
}

// A WebGL 2 context, optionally with one extension hidden: three.js then sees a context without it, as on
// a GPU or browser that does not expose it.
function makeRenderer(hiddenExtension) {
    const canvas = document.createElement('canvas');
    const gl = canvas.getContext('webgl2');
    if (!gl) return null;
    if (hiddenExtension) {
        const getExtension = gl.getExtension.bind(gl);
        gl.getExtension = (name) => (name === hiddenExtension ? null : getExtension(name));
        const getSupported = gl.getSupportedExtensions.bind(gl);
        gl.getSupportedExtensions = () => getSupported().filter((name) => name !== hiddenExtension);
    }
    return { gl, renderer: new THREE.WebGLRenderer({ canvas, context: gl }) };
}

const vertexShader = 'void main() { gl_Position = vec4(position.xy, 0.0, 1.0); }';
const fragmentShader = `
uniform sampler2D map;
uniform float lod;
uniform vec2 size;
void main() { gl_FragColor = textureLod(map, gl_FragCoord.xy / size, lod); }`;

// Every level of the texture as the GPU samples it: RGBA floats, rows bottom up as stored (row 0 of the
// file is t = 0, which is the framebuffer's row 0).
function readLevels(renderer, texture, width, height, levels) {
    const material = new THREE.ShaderMaterial({
        vertexShader, fragmentShader,
        uniforms: { map: { value: texture }, lod: { value: 0 }, size: { value: new THREE.Vector2() } },
    });
    const quad = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), material);
    quad.frustumCulled = false;
    const scene = new THREE.Scene();
    scene.add(quad);
    const camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
    const out = [];
    for (let level = 0; level < levels; ++level) {
        const w = Math.max(1, width >> level), h = Math.max(1, height >> level);
        const target = new THREE.WebGLRenderTarget(w, h, { type: THREE.FloatType, format: THREE.RGBAFormat,
            depthBuffer: false, minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter });
        material.uniforms.lod.value = level;
        material.uniforms.size.value.set(w, h);
        renderer.setRenderTarget(target);
        renderer.render(scene, camera);
        const pixels = new Float32Array(w * h * 4);
        renderer.readRenderTargetPixels(target, 0, 0, w, h, pixels);
        renderer.setRenderTarget(null);
        target.dispose();
        out.push({ w, h, pixels });
    }
    material.dispose();
    return out;
}

async function runCase(renderer, c) {
    const result = { name: c.name, hidden: c.hideExtension || null };
    const loader = new KTX2Loader();
    loader.detectSupport(renderer);
    const texture = await loader.loadAsync(c.ktx2);
    result.textureClass = texture.isCompressedTexture ? 'CompressedTexture' : texture.constructor.name;
    result.format = Object.keys(THREE).find((k) => k.endsWith('_Format') && THREE[k] === texture.format) ?? String(texture.format);
    result.mipmaps = texture.mipmaps.length;
    texture.minFilter = THREE.NearestMipmapNearestFilter;
    texture.magFilter = THREE.NearestFilter;
    const reference = new Float32Array(await (await fetch(c.reference)).arrayBuffer());
    const cross = c.crossReference ? new Float32Array(await (await fetch(c.crossReference)).arrayBuffer()) : null;
    const before = messages.length;
    const levels = readLevels(renderer, texture, c.width, c.height, c.levels);
    result.messages = messages.slice(before);
    result.levels = [];
    // What each read channel (R, G, B, A) is compared with: a channel of the reference, 'one' (reads 1) or
    // null (not compared). BC4/BC5: R (and G) the reference's channels.
    const channelMap = c.channelMap ?? [0, 1, 2, 3].map((k) => (k < c.channels ? k : null));
    let offset = 0;
    for (const { w, h, pixels } of levels) {
        let worst = 0, sum = 0, count = 0, largestRead = 0, crossWorst = 0;
        for (let i = 0; i < w * h; ++i) {
            for (const [k, source] of channelMap.entries()) {
                if (source === null) continue;
                const read = pixels[i * 4 + k];
                const expected = source === 'one' ? 1 : reference[offset + i * c.channels + source];
                const d = Math.abs(read - expected);
                worst = Math.max(worst, d);
                if (source === 'one') continue;  // the mean is over the map's values alone
                sum += d;
                ++count;
                largestRead = Math.max(largestRead, read);
                if (cross) crossWorst = Math.max(crossWorst, Math.abs(read - cross[offset + i * c.channels + source]));
            }
        }
        offset += w * h * c.channels;
        result.levels.push({ size: `${w}x${h}`, worstCodes: worst * 255, meanCodes: sum / count * 255, largestRead,
            crossWorstCodes: cross ? crossWorst * 255 : null });
    }
    texture.dispose();
    loader.dispose();
    return result;
}

async function main() {
    const report = { cases: [] };
    const shown = makeRenderer(null);
    if (!shown) {
        report.error = 'no WebGL 2 context';
        return report;
    }
    const gl = shown.gl;
    const debug = gl.getExtension('WEBGL_debug_renderer_info');
    report.renderer = debug ? gl.getParameter(debug.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
    report.extensions = gl.getSupportedExtensions();
    report.three = THREE.REVISION;
    report.floatTarget = gl.getExtension('EXT_color_buffer_float') !== null;
    const cases = await (await fetch('cases.json')).json();
    const hidden = {};
    for (const c of cases) {
        let renderer = shown.renderer;
        if (c.hideExtension) {
            hidden[c.hideExtension] ??= makeRenderer(c.hideExtension).renderer;
            renderer = hidden[c.hideExtension];
        }
        try {
            report.cases.push(await runCase(renderer, c));
        } catch (e) {
            report.cases.push({ name: c.name, hidden: c.hideExtension || null, error: String(e) });
        }
    }
    return report;
}

// The report goes back to the test's server, which ends the browser once it has it.
function send(report) {
    document.getElementById('result').textContent = JSON.stringify(report);
    return fetch('result', { method: 'POST', body: JSON.stringify(report) });
}
main().then(send, (e) => send({ error: String(e) }));
