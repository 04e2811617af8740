// Writes an MCAP file with the reference implementation, for core/mcap's reader to read:
//   node write.mjs FILE --compression none|zstd|lz4 [--no-chunks]
// Content (the C++ test knows the same pattern): three channels (ids from 0, as @mcap/core
// numbers them), two omgidl schemas and one channel without, MESSAGES messages whose log times
// are a permutation of 1 s + k ms (so chunks overlap in time), a metadata record and an
// attachment. Prints a JSON summary of what it wrote.
import { McapWriter } from "@mcap/core";
import { writeFileSync } from "node:fs";

import { crc32, loadCodecs, toJson } from "./common.mjs";

const args = process.argv.slice(2);
const path = args[0];
const compression = args[args.indexOf("--compression") + 1] ?? "none";
const useChunks = !args.includes("--no-chunks");
if (!path || !["none", "zstd", "lz4"].includes(compression)) {
  console.error("usage: node write.mjs FILE --compression none|zstd|lz4 [--no-chunks]");
  process.exit(2);
}

const MESSAGES = 500;
export const logTimeOf = (i) => 1_000_000_000n + BigInt((i * 7919) % MESSAGES) * 1_000_000n;
export function dataOf(i) {
  const d = new Uint8Array((i * 37) % 200);
  for (let k = 0; k < d.length; k++) d[k] = (i * 31 + k * 17) & 0xff;
  return d;
}

const { compressors } = await loadCodecs();
const pieces = [];
let size = 0;
const writable = {
  position: () => BigInt(size),
  write: async (buffer) => {
    pieces.push(Buffer.from(buffer));
    size += buffer.byteLength;
  },
};
const writer = new McapWriter({
  writable,
  useChunks,
  chunkSize: 4096,
  compressChunk: compression === "none" ? undefined : compressors[compression],
});
const text = (s) => new TextEncoder().encode(s);
await writer.start({ profile: "", library: "@mcap/core interop writer" });
const point = await writer.registerSchema({
  name: "interop::Point",
  encoding: "omgidl",
  data: text("module interop { struct Point { double x; double y; }; };\n"),
});
const label = await writer.registerSchema({
  name: "interop::Label",
  encoding: "omgidl",
  data: text("module interop { struct Label { string text; }; };\n"),
});
const channels = [
  await writer.registerChannel({ topic: "interop/points", schemaId: point, messageEncoding: "cdr", metadata: new Map([["k", "v"]]) }),
  await writer.registerChannel({ topic: "interop/labels", schemaId: label, messageEncoding: "cdr", metadata: new Map() }),
  await writer.registerChannel({ topic: "interop/raw", schemaId: 0, messageEncoding: "json", metadata: new Map() }),
];
await writer.addMetadata({ name: "interop", metadata: new Map([["writer", "@mcap/core"]]) });
// Without chunks @mcap/core 2.2.2 buffers messages unflushed and then indexes a later attachment
// at the stale writer position (its AttachmentIndex points before the attachment), so the
// attachment goes first there.
const attachmentAt = useChunks ? 100 : 0;
for (let i = 0; i < MESSAGES; i++) {
  if (i === attachmentAt) {
    await writer.addAttachment({ name: "notes.txt", mediaType: "text/plain", logTime: 5n, createTime: 6n, data: text("hello") });
  }
  const logTime = logTimeOf(i);
  await writer.addMessage({ channelId: channels[i % 3], sequence: i, logTime, publishTime: logTime + 1n, data: dataOf(i) });
}
await writer.end();
writeFileSync(path, Buffer.concat(pieces));

let sumOfDataCrcs = 0;
for (let i = 0; i < MESSAGES; i++) sumOfDataCrcs = (sumOfDataCrcs + crc32(dataOf(i))) >>> 0;
console.log(toJson({ file: path, size, messages: MESSAGES, channels, compression, useChunks, sumOfDataCrcs }));
