// SPDX-License-Identifier: Apache-2.0
// UvmsLogCount: decode every event of a UVMS run log (LCM event log) with LCM's Java API and the
// generated Java types (lcmgen/uvms_lcmtypes.jar), and count the messages per channel.
//
// Why: the Java types are what lcm-spy and other Java LCM tools decode with; this checks that
// the jar built from lcmtypes/*.lcm decodes a real log completely: every event must match a
// uvms type by its 8-byte fingerprint (LCM_FINGERPRINT of each class found in the jar) and
// decode without error. No build step: tests/tools/test_lcm_java.py compiles it with javac into
// a temporary directory; by hand, run it as a single-file source:
//   java -cp /usr/share/java/lcm.jar:UVMS_JAR tests/tools/java/UvmsLogCount.java UVMS_JAR LOG \
//        [--last CHANNEL]...
// Prints "CHANNEL count" per channel (sorted by name); then, for each --last, every field of
// that channel's last message as "LAST<TAB>CHANNEL<TAB>field<TAB>values": arrays flattened in
// row-major order and separated by spaces, numbers as Double.toString / Long.toString print
// them (they parse back to the same value), byte arrays as NUL-terminated UTF-8 text.
// Exit 0; exit 1 with one line "UvmsLogCount: error: ..." on stderr for an event no uvms type
// decodes (foreign or corrupted), a missing, unreadable or empty log, or a --last channel the
// log does not have; exit 2 on usage errors.
import java.io.EOFException;
import java.io.File;
import java.io.IOException;
import java.lang.reflect.Array;
import java.lang.reflect.Field;
import java.lang.reflect.Modifier;
import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.Enumeration;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.TreeMap;
import java.util.jar.JarEntry;
import java.util.jar.JarFile;

import lcm.logging.Log;

public final class UvmsLogCount {
  private static final String PREFIX = "UvmsLogCount: error: ";

  /** A bad input: reported on one line, exit 1. */
  static final class Failure extends Exception {
    private static final long serialVersionUID = 1L;

    Failure(String msg) {
      super(msg);
    }
  }

  private static final String USAGE = "usage: UvmsLogCount UVMS_JAR LOG [--last CHANNEL]...";

  public static void main(String[] args) {
    if (args.length == 1 && (args[0].equals("-h") || args[0].equals("--help"))) {
      System.out.println(USAGE);
      return;
    }
    List<String> lastChannels = new ArrayList<>();
    for (int i = 2; i + 1 < args.length && args[i].equals("--last"); i += 2) {
      lastChannels.add(args[i + 1]);
    }
    if (args.length < 2 || args.length != 2 + 2 * lastChannels.size()) {
      System.err.println(USAGE);
      System.exit(2);
    }
    try {
      run(args[0], args[1], lastChannels);
    } catch (Failure e) {
      System.err.println(PREFIX + e.getMessage());
      System.exit(1);
    }
  }

  static void run(String jar, String logPath, List<String> lastChannels) throws Failure {
    Map<Long, Class<?>> types = typesByFingerprint(jar);
    Map<String, Integer> counts = new TreeMap<>();
    Map<String, Object> last = new HashMap<>();
    for (Log.Event ev : readAll(logPath)) {
      Object msg = decode(types, ev, logPath);
      counts.merge(ev.channel, 1, Integer::sum);
      last.put(ev.channel, msg);
    }
    if (counts.isEmpty()) {
      throw new Failure(logPath + ": no LCM events (empty, or not an LCM log)");
    }
    for (String ch : lastChannels) {
      if (!last.containsKey(ch)) {
        throw new Failure(logPath + ": channel " + ch + " not in the log (has: "
            + String.join(", ", counts.keySet()) + ")");
      }
    }
    counts.forEach((ch, n) -> System.out.println(ch + " " + n));
    for (String ch : lastChannels) {
      printFields(ch, last.get(ch));
    }
  }

  /** Every class uvms/X.class in the jar (loaded from the class path), by LCM_FINGERPRINT. */
  static Map<Long, Class<?>> typesByFingerprint(String jar) throws Failure {
    Map<Long, Class<?>> types = new HashMap<>();
    try (JarFile jf = new JarFile(jar)) {
      for (Enumeration<JarEntry> e = jf.entries(); e.hasMoreElements(); ) {
        String name = e.nextElement().getName();
        if (!name.startsWith("uvms/") || !name.endsWith(".class") || name.contains("$")) {
          continue;
        }
        Class<?> cls = Class.forName(name.replace('/', '.').replace(".class", ""));
        types.put(cls.getField("LCM_FINGERPRINT").getLong(null), cls);
      }
    } catch (IOException e) {
      throw new Failure(jar + ": cannot read the types jar (" + e.getMessage() + ")");
    } catch (ReflectiveOperationException e) {
      throw new Failure(jar + ": not an lcm-gen type or not on the class path (" + e + ")");
    }
    if (types.isEmpty()) {
      throw new Failure(jar + ": no uvms types in the jar");
    }
    return types;
  }

  /** All events of the log, in order. */
  static List<Log.Event> readAll(String logPath) throws Failure {
    if (!new File(logPath).isFile()) {
      throw new Failure(logPath + ": no such log file");
    }
    List<Log.Event> events = new ArrayList<>();
    Log log = null;
    try {
      log = new Log(logPath, "r");
      while (true) {
        events.add(log.readNext());
      }
    } catch (EOFException e) {
      return events;  // the end of the log
    } catch (IOException e) {
      throw new Failure(logPath + ": cannot read as an LCM log after " + events.size()
          + " events (" + e.getMessage() + ")");
    } finally {
      try {
        if (log != null) log.close();
      } catch (IOException e) {
        // read-only: nothing to lose
      }
    }
  }

  /** The event's message, decoded with the uvms type of its fingerprint. */
  static Object decode(Map<Long, Class<?>> types, Log.Event ev, String logPath) throws Failure {
    String where = logPath + ": event " + ev.eventNumber + " on " + ev.channel + " (log_utime "
        + ev.utime + " us)";
    if (ev.data.length < 8) {
      throw new Failure(where + ": " + ev.data.length + " bytes, shorter than a fingerprint");
    }
    long fp = ByteBuffer.wrap(ev.data, 0, 8).getLong();
    Class<?> cls = types.get(fp);
    if (cls == null) {
      throw new Failure(where + ": no uvms type has fingerprint 0x" + Long.toHexString(fp)
          + " (a foreign or corrupted message)");
    }
    try {
      return cls.getConstructor(byte[].class).newInstance((Object) ev.data);
    } catch (ReflectiveOperationException e) {
      Throwable cause = e.getCause() != null ? e.getCause() : e;
      throw new Failure(where + ": cannot decode as " + cls.getName() + " (" + cause + ")");
    }
  }

  /** "LAST<TAB>CHANNEL<TAB>field<TAB>values" for every public instance field, in order. */
  static void printFields(String channel, Object msg) {
    for (Field f : msg.getClass().getFields()) {
      if (Modifier.isStatic(f.getModifiers())) continue;
      Object v;
      try {
        v = f.get(msg);
      } catch (IllegalAccessException e) {
        throw new IllegalStateException(e);  // public fields of a public class
      }
      System.out.println("LAST\t" + channel + "\t" + f.getName() + "\t" + text(v));
    }
  }

  /** A field value as text: arrays flattened with spaces, byte[] as NUL-terminated UTF-8. */
  static String text(Object v) {
    if (v instanceof byte[]) {
      byte[] b = (byte[]) v;
      int n = 0;
      while (n < b.length && b[n] != 0) n++;
      return new String(b, 0, n, StandardCharsets.UTF_8);
    }
    if (v == null || !v.getClass().isArray()) return String.valueOf(v);
    StringBuilder sb = new StringBuilder();
    for (int i = 0; i < Array.getLength(v); i++) {
      if (i > 0) sb.append(' ');
      sb.append(text(Array.get(v, i)));
    }
    return sb.toString();
  }

  private UvmsLogCount() {}
}
