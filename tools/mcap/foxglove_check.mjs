// Reads an MCAP file as Foxglove does, with the npm packages it is built on, and says
// whether every message of every channel decodes.
//
//   node tools/mcap/foxglove_check.mjs run.mcap [--json]
//
// - @mcap/core's McapIndexedReader opens the file through its summary and chunk
//   indexes (what Foxglove does with a seekable file), and McapStreamReader reads it
//   again front to back (what it falls back to): both must see the same messages, and
//   as many as the summary's statistics count.
// - Each channel is parsed as Foxglove's parseChannel does for message encoding `cdr`
//   with a `ros2msg` schema: @foxglove/rosmsg's parse(schema, { ros2: true }), then
//   @foxglove/rosmsg2-serialization's MessageReader for every message. A message that
//   leaves bytes unread (its schema and its bytes disagree) is an error too.
// - The header's profile must be `ros2` and every channel must carry the
//   `offered_qos_profiles` metadata that `ros2 bag` writes.
//
// Prints, per topic, its type, count and first message (long arrays cut); with
// --json, one JSON object instead. Exits 1 on any problem, listing each.

import { open } from "node:fs/promises";

import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { parse } from "@foxglove/rosmsg";
import { MessageReader } from "@foxglove/rosmsg2-serialization";

/** A file as @mcap/core's IReadable: its size and reads at an offset. */
async function readableOf(path) {
  const handle = await open(path, "r");
  const { size } = await handle.stat();
  return {
    handle,
    readable: {
      size: async () => BigInt(size),
      read: async (offset, length) => {
        const buffer = new Uint8Array(Number(length));
        const { bytesRead } = await handle.read(buffer, 0, buffer.length, Number(offset));
        if (bytesRead !== buffer.length) {
          throw new Error(`short read at ${offset}: ${bytesRead} of ${length} bytes`);
        }
        return buffer;
      },
    },
  };
}

/** A channel's decoder, as Foxglove's parseChannel makes it for `cdr` + `ros2msg`. */
function decoderOf(channel, schema) {
  if (channel.messageEncoding !== "cdr") {
    throw new Error(`message encoding ${channel.messageEncoding}, expected cdr`);
  }
  if (schema === undefined || schema.encoding !== "ros2msg") {
    throw new Error(`schema encoding ${schema?.encoding}, expected ros2msg`);
  }
  if (schema.data.length === 0) {
    throw new Error(`the schema of ${schema.name} is empty`);
  }
  const definitions = parse(new TextDecoder().decode(schema.data), { ros2: true });
  const reader = new MessageReader(definitions);
  return (data) => {
    const message = reader.readMessage(data);
    if (reader.lastReadHadTrailingBytes()) {
      throw new Error(`${data.byteLength - reader.lastReadByteLength()} bytes left unread`);
    }
    return message;
  };
}

/** `value` for printing: typed arrays and long arrays cut to their first elements. */
function shortened(value) {
  if (ArrayBuffer.isView(value)) {
    const head = Array.from(value.slice(0, 8), shortened);
    return value.length > 8 ? [...head, `... ${value.length} in all`] : head;
  }
  if (Array.isArray(value)) {
    const head = value.slice(0, 4).map(shortened);
    return value.length > 4 ? [...head, `... ${value.length} in all`] : head;
  }
  if (typeof value === "bigint") return String(value);
  if (typeof value === "number" && !Number.isFinite(value)) return String(value);
  if (value !== null && typeof value === "object") {
    return Object.fromEntries(Object.entries(value).map(([k, v]) => [k, shortened(v)]));
  }
  if (typeof value === "string" && value.length > 120) return `${value.slice(0, 120)}... (${value.length} chars)`;
  return value;
}

/** Every message's topic, read front to back by the stream reader. */
async function streamedCounts(path) {
  const handle = await open(path, "r");
  const bytes = await handle.readFile();
  await handle.close();
  const reader = new McapStreamReader({ validateCrcs: true });
  reader.append(bytes);
  const topics = new Map();
  const counts = new Map();
  let record;
  while ((record = reader.nextRecord()) !== undefined) {
    if (record.type === "Channel") topics.set(record.id, record.topic);
    if (record.type === "Message") {
      const topic = topics.get(record.channelId);
      counts.set(topic, (counts.get(topic) ?? 0) + 1);
    }
  }
  if (!reader.done()) throw new Error("the stream reader did not reach the file's end");
  return counts;
}

async function check(path) {
  const problems = [];
  const { handle, readable } = await readableOf(path);
  const reader = await McapIndexedReader.Initialize({ readable });
  if (reader.header.profile !== "ros2") problems.push(`profile "${reader.header.profile}", expected "ros2"`);
  const topics = new Map();
  for (const channel of reader.channelsById.values()) {
    const schema = reader.schemasById.get(channel.schemaId);
    const topic = { type: schema?.name, count: 0, first: undefined, errors: [] };
    topics.set(channel.topic, topic);
    if (!channel.metadata.has("offered_qos_profiles")) {
      topic.errors.push("no offered_qos_profiles metadata");
    }
    try {
      topic.decode = decoderOf(channel, schema);
    } catch (e) {
      topic.errors.push(`schema: ${e.message}`);
    }
  }
  let lastLogTime = -1n;
  for await (const message of reader.readMessages({ validateCrcs: true })) {
    const topic = topics.get(reader.channelsById.get(message.channelId).topic);
    topic.count += 1;
    if (message.logTime < lastLogTime) problems.push(`log time goes back at ${message.logTime}`);
    lastLogTime = message.logTime;
    if (topic.decode === undefined) continue;
    try {
      const decoded = topic.decode(message.data);
      topic.first ??= { logTime: String(message.logTime), message: shortened(decoded) };
    } catch (e) {
      if (topic.errors.length < 3) topic.errors.push(`message at ${message.logTime}: ${e.message}`);
    }
  }
  await handle.close();
  const streamed = await streamedCounts(path);
  const counted = reader.statistics?.channelMessageCounts;
  for (const [id, channel] of reader.channelsById) {
    const topic = topics.get(channel.topic);
    const inStatistics = counted?.get(id) ?? 0n;
    if (BigInt(topic.count) !== inStatistics) {
      topic.errors.push(`${topic.count} messages read, the statistics say ${inStatistics}`);
    }
    if ((streamed.get(channel.topic) ?? 0) !== topic.count) {
      topic.errors.push(`${topic.count} messages through the index, ${streamed.get(channel.topic) ?? 0} streamed`);
    }
    for (const error of topic.errors) problems.push(`${channel.topic}: ${error}`);
    delete topic.decode;
  }
  return { profile: reader.header.profile, library: reader.header.library, topics, problems };
}

const args = process.argv.slice(2);
const path = args.find((a) => !a.startsWith("--"));
if (path === undefined) {
  console.error("usage: node foxglove_check.mjs FILE.mcap [--json]");
  process.exit(2);
}
let result;
try {
  result = await check(path);
} catch (e) {
  // A file the readers refuse whole (no summary, a compression ARS does not write...).
  console.error(`${path}: ${e.message}`);
  process.exit(1);
}
if (args.includes("--json")) {
  console.log(JSON.stringify({ ...result, topics: Object.fromEntries(result.topics) }, null, 1));
} else {
  console.log(`${path}: profile ${result.profile}, written by ${result.library}`);
  for (const [name, topic] of result.topics) {
    console.log(`\n${name} (${topic.type}): ${topic.count} messages`);
    if (topic.first !== undefined) console.log(JSON.stringify(topic.first, null, 1));
  }
  console.log(result.problems.length === 0 ? "\nevery message decoded" : `\nPROBLEMS:\n${result.problems.join("\n")}`);
}
process.exit(result.problems.length === 0 ? 0 : 1);
