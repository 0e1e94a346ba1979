// The zstd chunk decompressor @mcap/core's readers take: fzstd (plain JavaScript, works offline),
// checked against the size the chunk record declares.
import { createRequire } from 'node:module';

const require = createRequire(new URL('../../web/package.json', import.meta.url));
const { decompress } = require('fzstd');

export const decompressHandlers = {
  zstd: (buffer, size) => {
    const out = decompress(buffer);
    if (BigInt(out.length) !== size) throw new Error(`zstd: ${out.length} bytes, not ${size}`);
    return out;
  },
};
