//! Launch rules on their own: `[N]` copies, name clashes, `max`, first matching rule.

use goal::env::EntityInfo;
use goal::mas::launch::{Launch, Launcher};

fn launcher(text: &str) -> Launcher {
    let (mas, diags) = goal::syntax::mas2g::parse(text, "t.mas2g");
    assert!(diags.iter().all(|d| !d.is_error()), "{diags:?}");
    Launcher::new(&mas.launch_rules)
}

fn bot(n: usize) -> EntityInfo {
    EntityInfo {
        name: format!("Bot{n}"),
        kind: "bot".into(),
    }
}

fn names(ls: &[Launch]) -> Vec<String> {
    ls.iter().map(|l| l.name.clone()).collect()
}

const FILES: &str = "agentfiles { \"a.goal\". \"b.goal\". }\n";

#[test]
fn copies_are_numbered_and_clashes_get_a_counter() {
    let mut l = launcher(&format!(
        "{FILES} launchpolicy {{ launch w:a[3]. launch a. launch a. launch solo:b[1]. }}"
    ));
    let got = l.unconditional();
    assert_eq!(names(&got), ["w1", "w2", "w3", "a", "a1", "solo"]);
    assert!(got.iter().all(|l| l.entity.is_none()));
    assert_eq!(got[5].reference, "b");
}

#[test]
fn max_and_first_matching_rule() {
    let mut l = launcher(&format!(
        "{FILES} launchpolicy {{
            when [type = bot, max = 2]@env do launch *:a.
            when [type = robot]@env do launch never:b.
            when entity@env do launch spare:b.
        }}"
    ));
    assert!(l.unconditional().is_empty());
    let mut all = Vec::new();
    for n in 1..=4 {
        all.extend(l.entity(&bot(n)).expect("a rule matches"));
    }
    let got: Vec<(String, String, Option<String>)> = all
        .into_iter()
        .map(|l| (l.name, l.reference, l.entity))
        .collect();
    let g = |n: &str, r: &str, e: &str| (n.to_string(), r.to_string(), Some(e.to_string()));
    assert_eq!(
        got,
        vec![
            g("Bot1", "a", "Bot1"),
            g("Bot2", "a", "Bot2"),
            g("spare", "b", "Bot3"),
            g("spare1", "b", "Bot4"),
        ]
    );
}

#[test]
fn no_matching_rule_is_none() {
    let mut l = launcher(&format!(
        "{FILES} launchpolicy {{ when [name = 'Bot9']@env do launch *:a. }}"
    ));
    assert_eq!(l.entity(&bot(1)), None);
    let got = l.entity(&bot(9)).expect("matches by name");
    assert_eq!(names(&got), ["Bot9"]);
}

#[test]
fn copies_of_entity_agents() {
    let mut l = launcher(&format!(
        "{FILES} launchpolicy {{ when entity@env do launch *:a[2], watcher:b. }}"
    ));
    let got = l.entity(&bot(1)).expect("matches");
    assert_eq!(names(&got), ["Bot11", "Bot12", "watcher"]);
    assert!(got.iter().all(|l| l.entity.as_deref() == Some("Bot1")));
}
