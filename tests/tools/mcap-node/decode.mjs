// Decodes every message of an MCAP recording as Foxglove and Lichtblick do, and prints what it
// found as JSON:   node decode.mjs FILE
// Per channel: the schema (encoding omgidl) is parsed with @foxglove/omgidl-parser and every
// message (encoding cdr) read with @foxglove/omgidl-serialization's MessageReader into a plain
// object. Reports per topic the messages, how many decoded, the first error, the first and last
// decoded message (bigints as strings, byte arrays as their length), and how many messages have
// a header.stamp_ns equal to their publish time. Exits 1 on a file @mcap/core cannot read.
import { McapIndexedReader } from "@mcap/core";
import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader } from "@foxglove/omgidl-serialization";
import { readFileSync } from "node:fs";

import { loadCodecs, toJson } from "./common.mjs";

const path = process.argv[2];
if (!path) {
  console.error("usage: node decode.mjs FILE");
  process.exit(2);
}
const bytes = new Uint8Array(readFileSync(path));
const { decompressHandlers } = await loadCodecs();
const readable = {
  size: async () => BigInt(bytes.length),
  read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
};
const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });

// Large arrays (images, range data) are summarised by their length.
function brief(value) {
  if (ArrayBuffer.isView(value)) return { length: value.length };
  if (Array.isArray(value)) return value.length > 16 ? { length: value.length } : value.map(brief);
  if (value && typeof value === "object") {
    return Object.fromEntries(Object.entries(value).map(([k, v]) => [k, brief(v)]));
  }
  return value;
}

const readers = new Map();  // channel id -> MessageReader or an Error
const topics = {};
for (const c of reader.channelsById.values()) {
  const schema = reader.schemasById.get(c.schemaId);
  const t = (topics[c.topic] = {
    schemaName: schema?.name ?? null,
    schemaEncoding: schema?.encoding ?? null,
    messageEncoding: c.messageEncoding,
    messages: 0,
    decoded: 0,
    stampIsPublishTime: 0,
    firstError: null,
    first: null,
    last: null,
  });
  try {
    if (!schema) throw new Error("no schema");
    if (schema.encoding !== "omgidl") throw new Error(`schema encoding ${schema.encoding}`);
    const text = new TextDecoder().decode(schema.data);
    readers.set(c.id, new MessageReader(schema.name, parseIDL(text)));
  } catch (e) {
    readers.set(c.id, e);
    t.firstError = `schema: ${e.message}`;
  }
}
let messages = 0;
for await (const m of reader.readMessages({ validateCrcs: true })) {
  const c = reader.channelsById.get(m.channelId);
  const t = topics[c.topic];
  t.messages++;
  messages++;
  const r = readers.get(m.channelId);
  if (r instanceof Error) continue;
  try {
    const msg = r.readMessage(m.data);
    t.decoded++;
    if (msg?.header?.stamp_ns !== undefined && BigInt(msg.header.stamp_ns) === m.publishTime) {
      t.stampIsPublishTime++;
    }
    const b = brief(msg);
    if (t.first === null) t.first = b;
    t.last = b;
  } catch (e) {
    if (t.firstError === null) t.firstError = `message ${t.messages}: ${e.message}`;
  }
}
console.log(toJson({ messages, topics }));
