// Compares the messages of one topic in two MCAP files, read with the reference TypeScript
// reader (@mcap/core) as a stream: the same count, and each message's bytes and log time equal
// in order. Prints {"topic", "a", "b", "same"}; exits 0 only if they are the same.
//
// Usage: node compare_topic.mjs A.mcap B.mcap TOPIC

import { readFile } from "node:fs/promises";

import lz4 from "@foxglove/wasm-lz4";
import * as zstd from "@foxglove/wasm-zstd";
import { McapStreamReader } from "@mcap/core";

const decompressHandlers = {
  zstd: (buffer, decompressedSize) => zstd.decompress(buffer, Number(decompressedSize)),
  lz4: (buffer, decompressedSize) => lz4(buffer, Number(decompressedSize)),
};

async function messagesOf(path, topic) {
  const reader = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  reader.append(await readFile(path));
  const topics = new Map();
  const out = [];
  for (let record; (record = reader.nextRecord()); ) {
    if (record.type === "Channel") topics.set(record.id, record.topic);
    if (record.type === "Message" && topics.get(record.channelId) === topic) {
      out.push({ time: record.logTime, data: Buffer.from(record.data) });
    }
  }
  if (!reader.done()) throw new Error(`${path}: the stream ends inside a record`);
  return out;
}

const [a, b, topic] = process.argv.slice(2);
if (!topic) {
  console.error("usage: node compare_topic.mjs A.mcap B.mcap TOPIC");
  process.exit(2);
}
await Promise.all([zstd.isLoaded, lz4.isLoaded]);
const x = await messagesOf(a, topic);
const y = await messagesOf(b, topic);
let same = x.length === y.length && x.length > 0;
for (let i = 0; same && i < x.length; ++i) {
  same = x[i].time === y[i].time && x[i].data.equals(y[i].data);
}
console.log(JSON.stringify({ topic, a: x.length, b: y.length, same }));
process.exit(same ? 0 : 1);
