// three.js's own KTX2Loader, in headless Chromium (SwiftShader's WebGL 2), loading the BC4, BC5 and ASTC
// KTX2 files heightpack writes: each mip level is drawn and read back as floats (three_ktx2_page.mjs) and
// compared texel by texel with heightpack's reader's decode (heightpack_decoded_levels), which
// tests/viewer/block_upload_test.cpp holds to Mesa's GPU decode within 1.5 codes. The same bound here for
// BC: RGTC decoders may round the interpolated value to 8 bits or not. ASTC: heightpack's decode is
// astcenc's UNORM16, WebGL's LDR decode 8 bits a channel (the UNORM16's top byte), so within one code;
// each ASTC case is also compared with another format's decode of the same map, which must miss the
// bound (the comparison can fail). One file more is loaded through a context that hides
// EXT_texture_compression_rgtc, for what three.js does where a GPU lacks it; an ASTC 8x8 file, which
// three.js r180's KTX2Loader has no format for, must be refused.
//   node three_ktx2_test.mjs HEIGHTPACK DECODED_LEVELS NPM_DIR SOURCE_DIR WORK_DIR
import { spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';

const [heightpack, decodedLevels, npmDir, sourceDir, workDir] = process.argv.slice(2);
const boundCodes = 1.5;  // worst |browser - reference| per channel, in 8-bit codes (1/255): BC
const astcBoundCodes = 1.0;  // the same for ASTC: an 8-bit decode of astcenc's UNORM16
const threeDir = path.join(npmDir, 'node_modules', 'three');
const pageDir = path.join(sourceDir, 'tests', 'browser');
const maps = path.join(sourceDir, 'examples', 'maps');

function fail(message) {
    console.error(`three_ktx2_browser: ${message}`);
    process.exit(1);
}

const loaderFile = path.join(threeDir, 'examples', 'jsm', 'loaders', 'KTX2Loader.js');
if (!fs.existsSync(loaderFile)) fail(`no three.js in ${npmDir}: run scripts/test.sh (it installs three from npm there)`);
const loaderSource = fs.readFileSync(loaderFile, 'utf8');
for (const entry of ['[ VK_FORMAT_BC4_UNORM_BLOCK ]: RED_RGTC1_Format', '[ VK_FORMAT_BC5_UNORM_BLOCK ]: RED_GREEN_RGTC2_Format',
    '[ VK_FORMAT_ASTC_4x4_UNORM_BLOCK ]: RGBA_ASTC_4x4_Format', '[ VK_FORMAT_ASTC_6x6_UNORM_BLOCK ]: RGBA_ASTC_6x6_Format'])
    if (!loaderSource.includes(entry)) fail(`${loaderFile} has no '${entry}' in its FORMAT_MAP: a three.js older than r180?`);
if (spawnSync('chromium', ['--version']).status !== 0) fail('no chromium on PATH (Debian\'s chromium: scripts/install-deps.sh)');

fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(workDir, { recursive: true });

function run(program, args) {
    const r = spawnSync(program, args, { encoding: 'utf8' });
    if (r.status !== 0) fail(`${path.basename(program)} ${args.join(' ')}: exit ${r.status}: ${r.stderr.trim()}`);
    return r.stdout;
}

// Plain heights in BC4 and xy normals in BC5, from every example map (8- and 16-bit, 256 and 512 wide,
// down to 1x1: levels smaller than a block), one supercompressed with Zstandard (the loader's zstd path).
const cases = [];
function addCase(name, args, extra = {}) {
    const ktx2 = `${name}.ktx2`, reference = `${name}.bin`;
    run(heightpack, [...args, '-o', path.join(workDir, ktx2)]);
    const meta = JSON.parse(run(decodedLevels, [path.join(workDir, ktx2), path.join(workDir, reference)]));
    cases.push({ name, ktx2, reference, hideExtension: null, ...meta, ...extra });
}
for (const map of ['swell', 'choppy', 'ripple', 'painted_not_tileable'])
    addCase(`${map}_bc4`, ['pack', path.join(maps, `${map}.png`), '--layout', 'plain', '--pixel-type', 'bc4', '-q']);
addCase('swell_bc4_zstd', ['pack', path.join(maps, 'swell.png'), '--layout', 'plain', '--pixel-type', 'bc4',
    '--compression', 'zstd', '-q']);
for (const [map, tile, height] of [['swell', '64m', '1.5m'], ['choppy', '16m', '0.4m'], ['ripple', '8m', '0.15m']])
    addCase(`${map}_n_bc5`, ['normal', path.join(maps, `${map}.png`), '--tile-size', tile, '--height', height,
        '--layout', 'xy', '--pixel-type', 'bc5', '-q']);
// ASTC (RGBA blocks): heights as luminance, R = G = B = the height and A = 1; xy normals as x in RGB and y
// in A (the file's KTXswizzle). channelMap: what R, G, B, A are compared with (three_ktx2_page.mjs).
// crossReference: the decode of the same map in another format, which the read levels must not match.
const astcHeights = { format: { 4: 'RGBA_ASTC_4x4_Format', 6: 'RGBA_ASTC_6x6_Format' }, channelMap: [0, 0, 0, 'one'] };
for (const map of ['swell', 'choppy'])
    for (const [side, other] of [[4, 6], [6, 4]])
        addCase(`${map}_astc${side}`, ['pack', path.join(maps, `${map}.png`), '--layout', 'plain', '--pixel-type',
            `astc-${side}x${side}`, '-q'], { astc: true, expectFormat: astcHeights.format[side],
            channelMap: astcHeights.channelMap, crossReference: `${map}_astc${other}.bin` });
addCase('ripple_n_astc4', ['normal', path.join(maps, 'ripple.png'), '--tile-size', '8m', '--height', '0.15m',
    '--layout', 'xy', '--pixel-type', 'astc-4x4', '-q'], { astc: true, expectFormat: 'RGBA_ASTC_4x4_Format',
    channelMap: [0, 0, 0, 1], crossReference: 'ripple_n_bc5.bin' });
addCase('swell_astc8', ['pack', path.join(maps, 'swell.png'), '--layout', 'plain', '--pixel-type', 'astc-8x8', '-q'],
    { expectError: 'Unsupported vkFormat' });
const hiddenCase = { ...cases[0], name: `${cases[0].name}_without_rgtc`, hideExtension: 'EXT_texture_compression_rgtc' };
cases.push(hiddenCase);
fs.writeFileSync(path.join(workDir, 'cases.json'), JSON.stringify(cases));

// ES modules do not load from file://: the page, three and the files over HTTP on a free local port. The
// page posts its report to /result.
const types = { '.html': 'text/html', '.mjs': 'text/javascript', '.js': 'text/javascript', '.json': 'application/json' };
let reportReceived;
const reportText = new Promise((resolve) => { reportReceived = resolve; });
const server = http.createServer((request, response) => {
    const url = decodeURIComponent(new URL(request.url, 'http://localhost').pathname);
    if (request.method === 'POST' && url === '/result') {
        let body = '';
        request.on('data', (d) => { body += d; });
        request.on('end', () => { response.writeHead(204).end(); reportReceived(body); });
        return;
    }
    const file = url.startsWith('/three/') ? path.join(threeDir, url.slice('/three/'.length))
        : url.startsWith('/three_ktx2_page.') ? path.join(pageDir, url.slice(1)) : path.join(workDir, url.slice(1));
    fs.readFile(file, (error, data) => {
        if (error) {
            response.writeHead(404).end();
            return;
        }
        response.writeHead(200, { 'Content-Type': types[path.extname(file)] ?? 'application/octet-stream' }).end(data);
    });
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const page = `http://127.0.0.1:${server.address().port}/three_ktx2_page.html`;

// The browser's console (three.js's warnings among it) goes to its stderr, kept for a failure's message.
const chromium = spawn('chromium', ['--headless=new', '--no-sandbox', '--use-angle=swiftshader',
    '--enable-unsafe-swiftshader', '--disable-gpu-sandbox', '--no-first-run', '--disable-extensions',
    '--enable-logging=stderr', '--v=0', `--user-data-dir=${path.join(workDir, 'profile')}`, page],
    { stdio: ['ignore', 'ignore', 'pipe'] });
let log = '';
chromium.stderr.on('data', (d) => { log += d; });
const closed = new Promise((resolve) => chromium.on('close', (code, signal) => resolve(signal ?? code)));
const waitSeconds = 120;
const text = await Promise.race([reportText, closed.then((how) => ({ how })),
    new Promise((resolve) => setTimeout(() => resolve({ how: `no report in ${waitSeconds} s` }), waitSeconds * 1000).unref())]);
chromium.kill('SIGKILL');
await closed;
server.close();
fs.writeFileSync(path.join(workDir, 'chromium.log'), log);
const consoleLines = () => log.split('\n').filter((l) => l.includes('CONSOLE')).slice(-5).join(' | ');
if (typeof text !== 'string') fail(`the page sent no report (chromium: ${text.how}); its console: ${consoleLines()}`);
const report = JSON.parse(text);
if (report.error) fail(`the page: ${report.error}; its console: ${consoleLines()}`);
fs.writeFileSync(path.join(workDir, 'report.json'), JSON.stringify(report, null, 1));

const has = (name) => report.extensions.includes(name);
console.log(`three.js r${report.three}, ${report.renderer}`);
for (const name of ['EXT_texture_compression_rgtc', 'WEBGL_compressed_texture_astc', 'EXT_color_buffer_float'])
    console.log(`  ${name}: ${has(name) ? 'exposed' : 'not exposed'}`);
if (!report.floatTarget) fail('no EXT_color_buffer_float: the levels cannot be read back as floats');
if (!has('EXT_texture_compression_rgtc'))
    console.log('NOT MEASURED: this context has no EXT_texture_compression_rgtc; only what three.js does without it is checked');

const failures = [];
for (const c of report.cases) {
    const expected = cases.find((e) => e.name === c.name);
    if (expected.expectError) {
        // KTX2Loader throws for a vkFormat missing from its FORMAT_MAP: loadAsync rejects, no texture.
        console.log(`${c.name}: ${c.error ? `refused: ${c.error}` : `loaded as ${c.textureClass} ${c.format}`}`);
        if (!c.error || !c.error.includes(expected.expectError))
            failures.push(`${c.name}: expected KTX2Loader to fail with '${expected.expectError}', got ${c.error ?? 'a texture'}`);
        continue;
    }
    if (c.error) {
        failures.push(`${c.name}: ${c.error}`);
        continue;
    }
    console.log(`${c.name}: ${c.textureClass} ${c.format}, ${c.mipmaps} levels` + (c.hidden ? ` (context without ${c.hidden})` : ''));
    for (const m of new Set(c.messages))
        console.log(`  three.js: ${m}` + (c.messages.filter((n) => n === m).length > 1 ? ` (x${c.messages.filter((n) => n === m).length})` : ''));
    if (expected.astc && !has('WEBGL_compressed_texture_astc')) {
        console.log(`  NOT MEASURED: this context has no WEBGL_compressed_texture_astc`);
        continue;
    }
    if (!expected.astc && (c.hidden || !has('EXT_texture_compression_rgtc'))) {
        // Without the extension three.js keeps the CompressedTexture, warns and uploads nothing: the
        // texture samples as black (0) everywhere.
        const warned = c.messages.some((m) => m.includes('unsupported compressed texture format'));
        const black = c.levels.every((l) => l.largestRead === 0);
        console.log(`  without RGTC: ${warned ? 'warned' : 'no warning'}, ${black ? 'every level reads 0' : 'levels read non-zero'}`);
        if (!warned || !black) failures.push(`${c.name}: expected three.js's warning and a black texture without RGTC`);
        continue;
    }
    const format = expected.expectFormat ?? (expected.channels === 1 ? 'RED_RGTC1_Format' : 'RED_GREEN_RGTC2_Format');
    const bound = expected.astc ? astcBoundCodes : boundCodes;
    if (c.textureClass !== 'CompressedTexture' || c.format !== format || c.mipmaps !== expected.levels)
        failures.push(`${c.name}: loaded as ${c.textureClass} ${c.format} with ${c.mipmaps} levels, not a CompressedTexture ${format} with ${expected.levels}`);
    for (const [i, l] of c.levels.entries()) {
        const crossText = l.crossWorstCodes === null ? '' : `; against ${expected.crossReference}: worst ${l.crossWorstCodes.toFixed(3)}`;
        console.log(`  level ${i} ${l.size}: worst ${l.worstCodes.toFixed(3)} codes, mean ${l.meanCodes.toFixed(4)} codes${crossText}`);
        if (!(l.worstCodes <= bound)) failures.push(`${c.name} level ${i}: worst ${l.worstCodes} codes > ${bound}`);
    }
    // The bound bites: level 0 read against another format's decode of the same map misses it.
    if (expected.crossReference && !(c.levels[0].crossWorstCodes > bound))
        failures.push(`${c.name}: level 0 is within ${bound} codes of ${expected.crossReference} too: the comparison cannot tell them apart`);
}
if (report.cases.length !== cases.length) failures.push(`${report.cases.length} cases reported of ${cases.length}`);
if (failures.length) fail(failures.join('\n  '));
console.log(`three_ktx2_browser: ${cases.length} files; every level of the BC files within ${boundCodes} codes, of the ASTC files within ${astcBoundCodes}, of heightpack's decode; ASTC 8x8 refused`);
