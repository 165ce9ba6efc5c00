// A static file server on 127.0.0.1 for the peer's page: ES modules and fetch() need http://,
// and the page must read Velvet's own resources (preset, schema, HDRI), not copies. URL paths
// are repository paths; only the folders in `roots` are served, nothing above them.
import { createServer } from 'node:http';
import { createReadStream } from 'node:fs';
import { stat } from 'node:fs/promises';
import path from 'node:path';

const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.json': 'application/json; charset=utf-8',
};

/**
 * Serves @p repo's files under the repository-relative folders @p roots.
 * Resolves to { url, close() } once listening on an ephemeral port.
 */
export function serve(repo, roots) {
  const allowed = roots.map((r) => path.join(repo, r) + path.sep);
  const server = createServer(async (request, response) => {
    const fail = (code) => response.writeHead(code).end();
    if (request.method !== 'GET') return fail(405);
    let file;
    try {
      file = path.join(repo, decodeURIComponent(new URL(request.url, 'http://x').pathname));
    } catch {
      return fail(400);
    }
    if (!allowed.some((root) => file.startsWith(root))) return fail(404);
    try {
      if (!(await stat(file)).isFile()) return fail(404);
    } catch {
      return fail(404);
    }
    response.writeHead(200, {
      'Content-Type': TYPES[path.extname(file)] ?? 'application/octet-stream',
      'Cache-Control': 'no-store',
    });
    createReadStream(file).pipe(response);
  });
  return new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(0, '127.0.0.1', () => {
      resolve({
        url: `http://127.0.0.1:${server.address().port}`,
        close: () => new Promise((done) => server.close(done)),
      });
    });
  });
}
